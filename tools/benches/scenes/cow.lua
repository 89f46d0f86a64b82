-- cow.obj (5 804 triangles) alone, seen from +z looking along −z (vertical field of view
-- 60°), one light: the cow row of the trace benchmark (`glint bench --trace`, 2048×2048).
local cow = gr.mesh('cow', '../../scenes/cs488/a4-2021plus/cow.obj')
cow:set_material(gr.material({0.84, 0.6, 0.53}, {0.3, 0.3, 0.3}, 20))
local root = gr.node('root')
root:add_child(cow)
gr.render(root, 'cow.png', 2048, 2048,
  {0, 0, 10}, {0, 0, -1}, {0, 1, 0}, 60,
  {0.3, 0.3, 0.3}, {gr.light({10, 10, 20}, {0.9, 0.9, 0.9}, {1, 0, 0})},
  {aa = 'none'})
