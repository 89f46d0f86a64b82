-- An animation: the camera swings round scrabble.lua's board, from 30 degrees to its
-- left to 30 degrees to its right, as `clock` runs from 0 to 1 (glint's --frames sets
-- `frame` and `clock`; without it this is the middle of the swing).
-- Render it with:  glint render scenes/scrabble-orbit.lua --frames 1-48 --width 320 --height 180
-- (outputs scrabble-orbit-0001.png to scrabble-orbit-0048.png; docs/farm.md runs it on a farm).

local t = clock or 0.5
local angle = math.rad(-30 + 60 * t)
-- The original camera's distance and height over the board's centre (0, 0, -0.6).
local radius, height, centre_z = 19.6, 17.5, -0.6
local eye = {radius * math.sin(angle), height, centre_z + radius * math.cos(angle)}
local view = {-eye[1], -height, centre_z - eye[3]}

-- scrabble.lua builds the scene and renders it once; this takes its gr.render call and
-- renders from the moving camera instead.
local render = gr.render
gr.render = function(root, _, width, height_px, _, _, up, fov, ambient, lights, options)
  render(root, 'scrabble-orbit.png', width, height_px, eye, view, up, fov, ambient, lights, options)
end
require('scrabble')
