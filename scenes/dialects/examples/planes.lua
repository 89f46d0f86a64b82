-- A scene in the planes dialect (../planes.lua):
--   glint render scenes/dialects/examples/planes.lua --prelude scenes/dialects/planes.lua
-- An "infinite" floor (gr.plane) out to the horizon, a wall of gr.nh_plane scaled 8×4,
-- a gr.nh_sheet and a disc (gr.disc) standing on the floor, and a box of gr.nh_rect.

floor_m = gr.material({0.8, 0.8, 0.8}, {0, 0, 0}, 1)
wall_m = gr.material({0.8, 0.2, 0.2}, {0, 0, 0}, 1)
sheet_m = gr.material({0.2, 0.8, 0.2}, {0, 0, 0}, 1)
disc_m = gr.material({0.2, 0.2, 0.9}, {0, 0, 0}, 1)
rect_m = gr.material({0.9, 0.7, 0.2}, {0, 0, 0}, 1)

root = gr.node('root')

floor = gr.plane('floor')
floor:set_material(floor_m)
root:add_child(floor)

wall = gr.nh_plane('wall')
wall:scale(8, 4, 1)
wall:translate(0, 2, -8)
wall:set_material(wall_m)
root:add_child(wall)

sheet = gr.nh_sheet('sheet', {-3, 1, -3}, 1.5, 2)
sheet:set_material(sheet_m)
root:add_child(sheet)

disc = gr.disc('disc', {3, 1.2, -3}, {0, 0, 1}, 1)
disc:set_material(disc_m)
root:add_child(disc)

rect = gr.nh_rect('rect', {-0.75, 0, -2}, {1.5, 0.8, 1})
rect:set_material(rect_m)
root:add_child(rect)

light = gr.light({2, 8, 6}, {0.8, 0.8, 0.8}, {1, 0, 0})
gr.render(root, 'dialect-planes.png', 320, 200, {0, 2, 8}, {0, -0.15, -1}, {0, 1, 0}, 50,
  {0.3, 0.3, 0.3}, {light}, {background = {0, 0, 0}})
