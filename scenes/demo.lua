-- glint's demo scene: a checkerboard of boxes, mirror and matte spheres, a mesh built
-- in Lua (a twisted star prism), and three coloured lights.
-- Render it with:  glint render scenes/demo.lua

gr.transform_order('pre')  -- explicit: this scene is written in the modern order

white  = gr.material({0.85, 0.85, 0.85}, {0.2, 0.2, 0.2}, 20)
dark   = gr.material({0.15, 0.15, 0.18}, {0.2, 0.2, 0.2}, 20)
red    = gr.material({0.8, 0.15, 0.1}, {0.6, 0.6, 0.6}, 60)
mirror = gr.material('mirror')
mirror:set_diffuse(0.05, 0.05, 0.05)
mirror:set_specular(0.8, 0.8, 0.8)
mirror:set_shininess(400)
mirror:set_reflection(0.85, 0.85, 0.9)
gold = gr.material('gold')
gold:set_diffuse(0.6, 0.45, 0.1)
gold:set_specular(0.7, 0.6, 0.3)
gold:set_shininess(80)
gold:set_reflection(0.25)

root = gr.node('root')

-- The floor: 10×10 tiles, 1 unit each, top at y = 0.
floor = gr.node('floor')
root:add_child(floor)
for i = 0, 9 do
  for j = 0, 9 do
    local tile = gr.cube('tile' .. i .. '_' .. j)
    tile:set_material(((i + j) % 2 == 0) and white or dark)
    tile:scale(1, 0.2, 1)
    tile:translate(i - 5, -0.2, j - 5)
    floor:add_child(tile)
  end
end

-- A mirror sphere and two matte ones.
big = gr.nh_sphere('mirror-ball', {-1.2, 1.3, -1}, 1.3)
big:set_material(mirror)
root:add_child(big)

small = gr.sphere('red-ball')
small:set_material(red)
small:scale(0.6, 0.6, 0.6)
small:translate(1.6, 0.6, 1.2)
root:add_child(small)

egg = gr.sphere('egg')
egg:set_material(white)
egg:scale(0.5, 0.8, 0.5)
egg:translate(-3, 0.8, 1.5)
root:add_child(egg)

-- A twisted five-pointed star prism, generated here: inline meshes use 0-based indices.
local verts, faces = {}, {}
local points, layers, height = 5, 12, 2.4
for layer = 0, layers do
  local y = height * layer / layers
  local twist = math.rad(72) * layer / layers
  for k = 0, 2 * points - 1 do
    local r = (k % 2 == 0) and 0.9 or 0.4
    local a = math.pi * k / points + twist
    verts[#verts + 1] = {r * math.cos(a), y, r * math.sin(a)}
  end
end
local ring = 2 * points
for layer = 0, layers - 1 do
  for k = 0, ring - 1 do
    local a = layer * ring + k
    local b = layer * ring + (k + 1) % ring
    faces[#faces + 1] = {a, b, b + ring, a + ring}
  end
end
-- Caps: polygons of ten corners, fan-triangulated by glint.
local bottom, top = {}, {}
for k = 0, ring - 1 do
  bottom[#bottom + 1] = ring - 1 - k
  top[#top + 1] = layers * ring + k
end
faces[#faces + 1] = bottom
faces[#faces + 1] = top
star = gr.mesh('star', verts, faces)
star:set_material(gold)
star:translate(1.8, 0, -1.8)
root:add_child(star)

lights = {
  gr.light({-6, 9, 8}, {0.75, 0.75, 0.7}, {1, 0, 0}),
  gr.light({7, 5, 4}, {0.35, 0.3, 0.5}, {1, 0, 0}),
  gr.light({0, 3, -6}, {0.4, 0.25, 0.15}, {1, 0.05, 0}),
}

gr.render(root, 'demo.png', 640, 400,
          {0, 3.2, 8.5}, {0, -0.35, -1}, {0, 1, 0}, 45,
          {0.25, 0.25, 0.3}, lights)
