-- The depth-of-field oracle scene (tests/oracle/depth_of_field.rs): three diffuse spheres
-- at three depths on a diffuse floor under one point light of attenuation {0, 0, 1}, the
-- middle sphere's front in focus. tools/oracle/depth_of_field.py builds the same scene in
-- Mitsuba 3 and renders the references; keep the two in step.
gr.transform_order('pre')

white = gr.material({0.8, 0.8, 0.8}, {0, 0, 0}, 1)
red = gr.material({0.8, 0.2, 0.15}, {0, 0, 0}, 1)
green = gr.material({0.2, 0.7, 0.3}, {0, 0, 0}, 1)
blue = gr.material({0.15, 0.3, 0.8}, {0, 0, 0}, 1)

root = gr.node('root')
floor = gr.cube('floor')
floor:set_material(white)
floor:scale(40, 1, 40)
floor:translate(-20, -1, -30)
root:add_child(floor)

for _, s in ipairs({
    {'near', {-1.2, 0.5, 1.0}, 0.5, red},
    {'middle', {0.3, 1.0, -3.0}, 1.0, green},
    {'far', {2.2, 1.5, -9.0}, 1.5, blue},
}) do
    local ball = gr.nh_sphere(s[1], s[2], s[3])
    ball:set_material(s[4])
    root:add_child(ball)
end

light = gr.light({3, 7, 4}, {40, 40, 40}, {0, 0, 1})
-- aperture and focus are the test's (--aperture, --focus); the focus 6.2 the test uses
-- is the middle sphere's front along the view direction.
gr.render(root, 'depth_of_field.png', 96, 72,
    {0, 2, 4}, {0, -0.2, -1}, {0, 1, 0}, 40,
    {0, 0, 0}, {light},
    {aa = 'uniform', samples = 32, background = {0, 0, 0}})
