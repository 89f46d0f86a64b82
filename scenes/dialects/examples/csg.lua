-- A scene in the csg dialect (../csg.lua):
--   glint render scenes/dialects/examples/csg.lua --prelude scenes/dialects/csg.lua
-- Left, a red box with a green ball cut out of its front (gr.difference); middle, the
-- lens where two balls overlap (gr.intersection); right, two balls joined (gr.union with
-- no name), and below, gr.intersect. Ambient light only: flat colours.

red = gr.material({0.9, 0.1, 0.1}, {0, 0, 0}, 1)
green = gr.material({0.1, 0.9, 0.1}, {0, 0, 0}, 1)
blue = gr.material({0.1, 0.1, 0.9}, {0, 0, 0}, 1)

root = gr.node('root')

box = gr.cube('box')
box:scale(2, 2, 2)
box:translate(-4, -1, -1)
box:set_material(red)
drill = gr.nh_sphere('drill', {-3, 0, 1}, 0.8)
drill:set_material(green)
dent = gr.difference('dent', box, drill)
root:add_child(dent)

a = gr.nh_sphere('a', {-0.6, 0, 0}, 1)
b = gr.nh_sphere('b', {0.6, 0, 0}, 1)
lens = gr.intersection('lens', a, b)
lens:set_material(blue)
root:add_child(lens)

c = gr.nh_sphere('c', {2.6, 0, 0}, 0.7)
d = gr.nh_sphere('d', {3.6, 0, 0}, 0.7)
pair = gr.union(c, d)
pair:set_material(green)
root:add_child(pair)

e = gr.nh_sphere('e', {-0.4, -2.2, 0}, 0.6)
f = gr.nh_sphere('f', {0.4, -2.2, 0}, 0.6)
small_lens = gr.intersect('small_lens', e, f)
small_lens:set_material(red)
root:add_child(small_lens)

gr.render(root, 'dialect-csg.png', 320, 200, {0, 0, 10}, {0, 0, -1}, {0, 1, 0}, 50,
  {1, 1, 1}, {})
