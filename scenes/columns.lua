-- glint's cylinder and cone scene: a colonnade of capped cylinders with conical roofs on a
-- floor, a double cone (hourglass), a truncated cone standing on its narrow end, and a
-- mirror cylinder lying on its side.
-- Render it with:  glint render scenes/columns.lua
--
-- gr.cylinder(name): radius 1 around the z axis, z from 0 to 1, capped.
-- gr.cone(name, zmin, zmax): x² + y² = z² between z = zmin and z = zmax, capped; with
-- zmin < 0 < zmax both nappes (a double cone touching at the tip).
-- rotate('x', -90) stands a primitive's z axis up along y.

gr.transform_order('pre')

stone = gr.material({0.8, 0.78, 0.7}, {0.3, 0.3, 0.3}, 30)
terracotta = gr.material({0.75, 0.3, 0.15}, {0.4, 0.3, 0.2}, 40)
floor_mat = gr.material({0.35, 0.4, 0.45}, {0.1, 0.1, 0.1}, 10)
teal = gr.material({0.1, 0.55, 0.5}, {0.6, 0.6, 0.6}, 80)
mirror = gr.material('mirror')
mirror:set_diffuse(0.05, 0.05, 0.05)
mirror:set_specular(0.8, 0.8, 0.8)
mirror:set_shininess(300)
mirror:set_reflection(0.8, 0.8, 0.85)

root = gr.node('root')

floor = gr.cube('floor')
floor:set_material(floor_mat)
floor:scale(14, 0.2, 12)
floor:translate(-7, -0.2, -8)
root:add_child(floor)

-- Four columns with conical roofs (tip up: rotate('x', 90) sends z to −y).
for i = 0, 3 do
  local x = -3.3 + 2.2 * i
  local column = gr.cylinder('column' .. i)
  column:set_material(stone)
  column:scale(0.35, 0.35, 2.4)
  column:rotate('x', -90)
  column:translate(x, 0, -2.5)
  root:add_child(column)

  local roof = gr.cone('roof' .. i, 0, 1)
  roof:set_material(terracotta)
  roof:scale(0.55, 0.55, 0.7)
  roof:rotate('x', 90)
  roof:translate(x, 3.1, -2.5)
  root:add_child(roof)
end

-- An hourglass: the double cone from z = −1 to z = 1.
hourglass = gr.cone('hourglass', -1, 1)
hourglass:set_material(teal)
hourglass:scale(0.6, 0.6, 0.7)
hourglass:rotate('x', -90)
hourglass:translate(-1.6, 0.7, 1.0)
root:add_child(hourglass)

-- A truncated cone on its narrow end (radius 0.3 at the floor, 0.9 at the top).
bucket = gr.cone('bucket', 0.5, 1.5)
bucket:set_material(terracotta)
bucket:scale(0.6, 0.6, 0.6)
bucket:rotate('x', -90)
bucket:translate(1.7, -0.3, 1.2)
root:add_child(bucket)

-- A mirror cylinder lying along x.
log = gr.cylinder('log')
log:set_material(mirror)
log:scale(0.45, 0.45, 2.2)
log:rotate('y', 90)
log:translate(-1.1, 0.45, 3.0)
root:add_child(log)

lights = {
  gr.light({-5, 8, 7}, {0.8, 0.78, 0.72}, {1, 0, 0}),
  gr.light({6, 4, 5}, {0.3, 0.3, 0.45}, {1, 0, 0}),
}

gr.render(root, 'columns.png', 320, 200,
          {0, 2.6, 9}, {0, -0.22, -1}, {0, 1, 0}, 45,
          {0.25, 0.25, 0.3}, lights)
