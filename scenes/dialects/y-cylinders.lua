-- Dialect prelude: cylinders standing on y, as most CS488 students' gr.cylinder did
-- (glint's stands on z).
--
--   glint render scene.lua --prelude scenes/dialects/y-cylinders.lua
--
-- The meaning assumed:
--
-- gr.cylinder(name)                 radius 1 around the y axis, y from −1 to 1, capped:
--                                   the cylinder that fits the unit sphere, centred
--                                   where gr.sphere is.
-- gr.cylinder(name, radius, height) radius and height given, still centred on the
--                                   origin (y from −height/2 to height/2).
--
-- It changes a call glint has (scenes written for glint expect z), so it is not in
-- all.lua: ask for it by name. The placement (node:set_placement) comes before the
-- node's own transforms, in either transform order. UVs are glint's cylinder's, turned
-- with it: u around the axis from +x, v up the side.

local builtin_cylinder = gr.cylinder

function gr.cylinder(name, radius, height, ...)
  if select('#', ...) > 0 or (radius ~= nil and height == nil) then
    error('gr.cylinder: this prelude (y-cylinders.lua) reads gr.cylinder(name) or '
      .. 'gr.cylinder(name, radius, height)', 2)
  end
  radius, height = radius or 1, height or 2
  for n, v in ipairs({radius, height}) do
    if type(v) ~= 'number' or not (v > 0) then
      error(string.format('gr.cylinder: argument %d (%s) must be a positive number, got %s',
        n + 1, n == 1 and 'radius' or 'height', tostring(v)), 2)
    end
  end
  local node = builtin_cylinder(name)
  -- z (glint's axis) to +y; x stays x, y goes to −z, keeping the frame right-handed.
  node:set_placement({0, -height / 2, 0}, {radius, 0, 0}, {0, 0, -radius}, {0, height, 0})
  return node
end
