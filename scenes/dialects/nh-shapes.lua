-- Dialect prelude: positioned cylinders and cones, as many CS488 tracers wrote them
-- (the way gr.nh_sphere and gr.nh_box place a sphere and a box).
--
--   glint render scene.lua --prelude scenes/dialects/nh-shapes.lua
--
-- Glint's gr.cylinder is radius 1 around the z axis from z = 0 to 1, and gr.cone(name,
-- zmin, zmax) the cone x² + y² = z²; these calls place them with node:set_placement,
-- which puts the primitive in its node's frame before the node's own transforms (so the
-- scene's scale, rotate and translate act on the placed solid in either transform order).
-- The meaning assumed:
--
-- gr.nh_cylinder(name, base, axis, radius, height)  a capped cylinder whose bottom cap is
--     centred at base, running `height` along the direction axis.
-- gr.nh_cylinder(name, base, radius, height)  the same standing on y (axis {0, 1, 0}): y
--     is up in most of these scenes.
-- gr.nh_cone(name, base, radius, height)  a capped cone standing on y: its base a disc of
--     that radius centred at base, its tip `height` above it.
-- gr.nh_cone(name, base, size)  the same with radius and height both `size` (glint's own
--     cone's 45° slope).
-- Other forms (a cone with a top radius, cylinders by y range) are refused with a
-- message: their meanings differ between tracers.

local checks = require('checks')
local fail, want_positive, want_vec3, cross =
  checks.fail, checks.want_positive, checks.want_vec3, checks.cross

local function unit(v)
  local len = math.sqrt(v[1] * v[1] + v[2] * v[2] + v[3] * v[3])
  return {v[1] / len, v[2] / len, v[3] / len}
end

local function times(v, s) return {v[1] * s, v[2] * s, v[3] * s} end

-- Unit vectors p, q across the unit axis a with p × q = a (a right-handed frame p, q, a).
local function across(a)
  local helper = math.abs(a[1]) < 0.5 and {1, 0, 0} or {0, 1, 0}
  local p = unit(cross(helper, a))
  return p, cross(a, p)
end

local Y = {0, 1, 0}

function gr.nh_cylinder(name, base, a, b, c, ...)
  local axis, radius, height = Y, a, b
  if type(a) == 'table' then axis, radius, height = a, b, c
  elseif c ~= nil then
    error('gr.nh_cylinder: this prelude (nh-shapes.lua) reads gr.nh_cylinder(name, base, '
      .. 'radius, height) or gr.nh_cylinder(name, base, axis, radius, height)', 2)
  end
  want_vec3('gr.nh_cylinder', 2, 'base', base)
  if axis ~= Y then want_vec3('gr.nh_cylinder', 3, 'axis', axis) end
  local n = type(a) == 'table' and 4 or 3
  want_positive('gr.nh_cylinder', n, 'radius', radius)
  want_positive('gr.nh_cylinder', n + 1, 'height', height)
  local len = math.sqrt(axis[1] ^ 2 + axis[2] ^ 2 + axis[3] ^ 2)
  if not (len > 0) then fail('gr.nh_cylinder', 3, 'axis', 'a non-zero direction', axis) end
  local k = unit(axis)
  local p, q = across(k)
  local node = gr.cylinder(name)
  node:set_placement(base, times(p, radius), times(q, radius), times(k, height))
  return node
end

function gr.nh_cone(name, base, radius, height, ...)
  if select('#', ...) > 0 then
    error('gr.nh_cone: this prelude (nh-shapes.lua) reads gr.nh_cone(name, base, radius, '
      .. 'height) or gr.nh_cone(name, base, size)', 2)
  end
  want_vec3('gr.nh_cone', 2, 'base', base)
  want_positive('gr.nh_cone', 3, 'radius', radius)
  if height == nil then height = radius end
  want_positive('gr.nh_cone', 4, 'height', height)
  -- Glint's cone from z = 0 (the tip) to z = 1 (radius 1), turned tip up: z runs down
  -- from the tip, and the frame stays right-handed (x × y = z).
  local tip = {base[1], base[2] + height, base[3]}
  local node = gr.cone(name, 0, 1)
  node:set_placement(tip, {radius, 0, 0}, {0, 0, radius}, {0, -height, 0})
  return node
end
