-- glint's torus scene: a chain of three linked rings, a mirror ring standing on its edge,
-- a fat torus lying flat and a spindle torus (rout > rin, the self-intersecting kind),
-- on a checkerboard floor.
-- Render it with:  glint render scenes/tori.lua

gr.transform_order('pre')

white  = gr.material({0.85, 0.85, 0.85}, {0.2, 0.2, 0.2}, 20)
dark   = gr.material({0.15, 0.15, 0.18}, {0.2, 0.2, 0.2}, 20)
red    = gr.material({0.8, 0.15, 0.1}, {0.6, 0.6, 0.6}, 60)
blue   = gr.material({0.15, 0.3, 0.8}, {0.6, 0.6, 0.6}, 60)
green  = gr.material({0.15, 0.65, 0.25}, {0.5, 0.5, 0.5}, 40)
mirror = gr.material('mirror')
mirror:set_diffuse(0.05, 0.05, 0.05)
mirror:set_specular(0.8, 0.8, 0.8)
mirror:set_shininess(400)
mirror:set_reflection(0.8, 0.8, 0.85)
gold = gr.material({0.6, 0.45, 0.1}, {0.7, 0.6, 0.3}, 80)

root = gr.node('root')

-- The floor: 10×10 tiles, top at y = 0.
for i = 0, 9 do
  for j = 0, 9 do
    local tile = gr.cube('tile' .. i .. '_' .. j)
    tile:set_material(((i + j) % 2 == 0) and white or dark)
    tile:scale(1, 0.2, 1)
    tile:translate(i - 5, -0.2, j - 5)
    root:add_child(tile)
  end
end

-- A chain of three linked rings (rin 0.8, rout 0.15) along x, 0.8 apart: the middle
-- one upright (the XY plane), its neighbours flat (turned into the XZ plane), so each
-- passes once through the next one's hole. The upright one stands on the floor.
local colours = {red, blue, green}
for k = 0, 2 do
  local ring = gr.torus('link' .. k, 0.8, 0.15)
  ring:set_material(colours[k + 1])
  if k % 2 == 0 then
    ring:rotate('x', 90)
  end
  ring:translate(-2.6 + 0.8 * k, 0.95, 1.0)
  root:add_child(ring)
end

-- A mirror ring standing on its edge behind.
standing = gr.torus('mirror-ring', 1.1, 0.3)
standing:set_material(mirror)
standing:rotate('y', 25)
standing:translate(1.6, 1.4, -1.8)
root:add_child(standing)

-- A fat torus lying flat (axis z turned to y).
fat = gr.torus('fat', 0.6, 0.4)
fat:set_material(gold)
fat:rotate('x', 90)
fat:translate(2.4, 0.4, 1.4)
root:add_child(fat)

-- A spindle torus (rout > rin): an apple shape, dimpled at the poles.
spindle = gr.torus('spindle', 0.35, 0.6)
spindle:set_material(white)
spindle:rotate('x', 90)
spindle:translate(-3.4, 0.6, -1.4)
root:add_child(spindle)

lights = {
  gr.light({-6, 9, 8}, {0.75, 0.75, 0.7}, {1, 0, 0}),
  gr.light({7, 5, 4}, {0.35, 0.3, 0.5}, {1, 0, 0}),
}

gr.render(root, 'tori.png', 640, 400,
          {0, 3.2, 8.5}, {0, -0.35, -1}, {0, 1, 0}, 45,
          {0.25, 0.25, 0.3}, lights)
