-- N random triangles in the unit cube, read from random-triangles.obj beside this file
-- (tools/benches/compare.sh writes it with tools/benches/random_triangles.py N SEED: the triangles
-- of glint's own `glint bench` sweep), seen from +z as `glint bench` sees them, one light.
local soup = gr.mesh('soup', 'random-triangles.obj')
soup:set_material(gr.material({0.7, 0.7, 0.7}, {0.0, 0.0, 0.0}, 1))
local root = gr.node('root')
root:add_child(soup)
gr.render(root, 'random-triangles.png', 1024, 1024,
  {0.5, 0.5, 3}, {0, 0, -1}, {0, 1, 0}, 40,
  {0.1, 0.1, 0.1}, {gr.light({0.5, 3, 3}, {0.9, 0.9, 0.9}, {1, 0, 0})},
  {aa = 'none'})
