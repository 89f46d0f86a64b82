-- glint's depth-of-field scene: a row of spheres receding along a floor, seen through a
-- thin lens focused on the third; the nearer and farther ones blur by their circles of
-- confusion. A mirror sphere shows its neighbours, sharp where they are in focus.
-- Render it with:  glint render scenes/depth-of-field.lua
-- (--aperture 0 for the pinhole; --focus 4 to focus on the nearest sphere.)

gr.transform_order('pre')

floor_mat = gr.material({0.75, 0.74, 0.7}, {0.1, 0.1, 0.1}, 10)
colours = {
    {0.85, 0.2, 0.15}, {0.9, 0.6, 0.1}, {0.25, 0.7, 0.3}, {0.2, 0.45, 0.85}, {0.6, 0.3, 0.8},
}
mirror = gr.material({0.05, 0.05, 0.05}, {0.7, 0.7, 0.7}, 300)
mirror:set_reflection(0.8, 0.8, 0.8)

root = gr.node('root')

floor = gr.cube('floor')
floor:set_material(floor_mat)
floor:scale(30, 0.2, 40)
floor:translate(-15, -0.2, -36)
root:add_child(floor)

-- Spheres from 4 to 20 units in front of the eye, stepping left to right.
for i, c in ipairs(colours) do
    local ball = gr.nh_sphere('ball' .. i, {-3.2 + 1.6 * i, 0.8, 6 - 4 * i}, 0.8)
    ball:set_material(gr.material(c, {0.4, 0.4, 0.4}, 40))
    root:add_child(ball)
end

chrome = gr.nh_sphere('chrome', {2.6, 0.6, -3.0}, 0.6)
chrome:set_material(mirror)
root:add_child(chrome)

key = gr.light({-6, 10, 6}, {0.9, 0.88, 0.8}, {1, 0, 0})
fill = gr.light({8, 6, -4}, {0.3, 0.32, 0.4}, {1, 0, 0})

-- Focused on the third sphere (its centre 12 units along the view direction). Uniform
-- 6×6 AA: each pixel's 36 samples take its lens sequence's first 36 points, so the blur
-- converges where adaptive AA's five samples of an unsplit pixel would leave it grainy.
gr.render(root, 'depth-of-field.png', 320, 200,
    {0, 1.6, 6}, {0, -0.12, -1}, {0, 1, 0}, 40,
    {0.25, 0.25, 0.25}, {key, fill},
    {aa = 'uniform', samples = 6, aperture = 0.18, focus = 12})
