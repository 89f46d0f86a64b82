-- The bumpy torus of tools/benches/bumpy_torus.py, read from mesh.obj beside this file
-- (tools/benches/meshload.sh writes it), seen at an angle, one light.
local torus = gr.mesh('torus', 'mesh.obj')
torus:set_material(gr.material({0.7, 0.6, 0.5}, {0.3, 0.3, 0.3}, 20))
local root = gr.node('root')
root:add_child(torus)
gr.render(root, 'image.png', 640, 480,
  {0, -3, 2.2}, {0, 3, -2.2}, {0, 0, 1}, 50,
  {0.1, 0.1, 0.1}, {gr.light({2, -3, 4}, {0.9, 0.9, 0.9}, {1, 0, 0})},
  {aa = 'none'})
