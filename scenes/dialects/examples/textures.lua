-- A scene in the textures dialect (../textures.lua):
--   glint render scenes/dialects/examples/textures.lua --prelude scenes/dialects/textures.lua
-- Left, a box whose material has m:set_texture (glint's UV grid: red rises to the right,
-- green upwards); middle, two boxes sharing one yellow material, the upper one given
-- node:set_texture(gr.texture(...)) (the lower one stays yellow); right, a box of
-- gr.image_material; in front, a ball with m:set_bumpmap.

grid = '../../../textures/uv-grid.png'

yellow = gr.material({0.9, 0.9, 0.1}, {0, 0, 0}, 1)
textured = gr.material({1, 1, 1}, {0, 0, 0}, 1)
textured:set_texture(grid)
image = gr.image_material(grid, {1, 1}, {0, 0, 0}, 10, false)
bumpy = gr.material({0.7, 0.7, 0.7}, {0.3, 0.3, 0.3}, 20)
bumpy:set_bumpmap('../../../textures/bumps.png', 0.05)

root = gr.node('root')

function box(name, m, x, y, s)
  local b = gr.cube(name)
  b:scale(s, s, 0.5)
  b:translate(x - s / 2, y - s / 2, -1)
  if m then b:set_material(m) end
  root:add_child(b)
  return b
end
box('material_texture', textured, -3.2, 0.3, 2.6)
upper = box('node_texture', nil, 0, 1.2, 1.8)
upper:set_texture(gr.texture(grid))
upper:set_material(yellow) -- after set_texture: either order works
box('untextured', yellow, 0, -1.2, 1.8)
box('image_material', image, 3.2, 0.3, 2.6)

ball = gr.nh_sphere('bumpy_ball', {0, -3.1, 1}, 0.9)
ball:set_material(bumpy)
root:add_child(ball)

light = gr.light({0, 0, 12}, {0.6, 0.6, 0.6}, {1, 0, 0})
gr.render(root, 'dialect-textures.png', 320, 240, {0, 0, 10}, {0, 0, -1}, {0, 1, 0}, 50,
  {0.6, 0.6, 0.6}, {light})
