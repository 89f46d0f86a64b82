-- A scene in the y-cylinders dialect (../y-cylinders.lua):
--   glint render scenes/dialects/examples/y-cylinders.lua --prelude scenes/dialects/y-cylinders.lua
-- Left, gr.cylinder as most students' tracers had it: radius 1 around y, y from −1 to 1,
-- seen from the side (a rectangle, not glint's cap-on disc); right, one of radius 0.5
-- and height 3 tilted by the scene's own rotate. Ambient light only: flat colours.

red = gr.material({0.9, 0.1, 0.1}, {0, 0, 0}, 1)
green = gr.material({0.1, 0.9, 0.1}, {0, 0, 0}, 1)

root = gr.node('root')

c = gr.cylinder('unit')
c:translate(-2, 0, 0)
c:set_material(red)
root:add_child(c)

tall = gr.cylinder('tall', 0.5, 3)
tall:rotate('z', -30)
tall:translate(2, 0, 0)
tall:set_material(green)
root:add_child(tall)

gr.render(root, 'dialect-y-cylinders.png', 320, 200, {0, 0, 10}, {0, 0, -1}, {0, 1, 0}, 50,
  {1, 1, 1}, {})
