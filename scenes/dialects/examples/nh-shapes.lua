-- A scene in the nh-shapes dialect (../nh-shapes.lua):
--   glint render scenes/dialects/examples/nh-shapes.lua --prelude scenes/dialects/nh-shapes.lua
-- Left, a cylinder standing on y (gr.nh_cylinder(name, base, radius, height)); middle, a
-- cone standing on its base; right, a cylinder lying along x (the form with an axis).
-- Ambient light only: flat colours.

red = gr.material({0.9, 0.1, 0.1}, {0, 0, 0}, 1)
green = gr.material({0.1, 0.9, 0.1}, {0, 0, 0}, 1)
blue = gr.material({0.1, 0.1, 0.9}, {0, 0, 0}, 1)

root = gr.node('root')

standing = gr.nh_cylinder('standing', {-3, -1, 0}, 0.5, 2)
standing:set_material(red)
root:add_child(standing)

cone = gr.nh_cone('cone', {0, -1, 0}, 1, 2)
cone:set_material(green)
root:add_child(cone)

lying = gr.nh_cylinder('lying', {2, 0, 0}, {1, 0, 0}, 0.4, 2)
lying:set_material(blue)
root:add_child(lying)

gr.render(root, 'dialect-nh-shapes.png', 320, 200, {0, 0, 10}, {0, 0, -1}, {0, 1, 0}, 50,
  {1, 1, 1}, {})
