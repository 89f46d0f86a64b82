-- A scene in the materials dialect (../materials.lua):
--   glint render scenes/dialects/examples/materials.lua --prelude scenes/dialects/materials.lua
-- Left, a mirror ball (gr.mirror_material) showing the green wall behind the camera;
-- right, a glass ball (gr.material with reflect 0 and index 1.5) turning the red-over-blue
-- wall behind it upside down; in the middle, a half mirror (reflect 0.5) and a small clear
-- ball (gr.clear_material). Lit by ambient light only, so every colour is flat.

red = gr.material({0.9, 0.1, 0.1}, {0, 0, 0}, 1)
blue = gr.material({0.1, 0.1, 0.9}, {0, 0, 0}, 1)
green = gr.material({0.1, 0.9, 0.1}, {0, 0, 0}, 1)
mirror = gr.mirror_material({0, 0, 0}, {0.9, 0.9, 0.9}, 100, 0)
glass = gr.material({0, 0, 0}, {0, 0, 0}, 1, 0, 1.5)
half_mirror = gr.material({0.3, 0.3, 0.3}, {0.5, 0.5, 0.5}, 20, 0.5)
clear = gr.clear_material({0, 0, 0}, {0, 0, 0}, 1, 0, 1.5)

root = gr.node('root')

function slab(name, m, x, y, z, sx, sy, sz)
  local b = gr.cube(name)
  b:scale(sx, sy, sz)
  b:translate(x, y, z)
  b:set_material(m)
  root:add_child(b)
end
slab('wall_top', red, -20, 0, -6, 40, 20, 1)
slab('wall_bottom', blue, -20, -20, -6, 40, 20, 1)
slab('behind_camera', green, -50, -50, 30, 100, 100, 1)

function ball(name, m, x, y, r)
  local s = gr.nh_sphere(name, {x, y, 0}, r)
  s:set_material(m)
  root:add_child(s)
end
ball('mirror_ball', mirror, -2.8, 0, 1.2)
ball('glass_ball', glass, 2.8, 0, 1.5)
ball('half_mirror_ball', half_mirror, 0, 1.2, 0.6)
ball('clear_ball', clear, 0, -1.2, 0.6)

gr.render(root, 'dialect-materials.png', 320, 200, {0, 0, 10}, {0, 0, -1}, {0, 1, 0}, 50,
  {1, 1, 1}, {})
