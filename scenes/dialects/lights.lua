-- Dialect prelude: area lights the way many CS488 tracers wrote them.
--
--   glint render scene.lua --prelude scenes/dialects/lights.lua
--
-- Glint's soft light is the parallelogram gr.area_light(centre, u, v, colour, falloff[, n])
-- (n×n jittered samples, each a point light with 1/n² of the colour, so the light's
-- total is `colour` whatever its size). The meaning assumed:
--
-- gr.arealight(position, colour, falloff, w, h[, n])  a w×h rectangle centred at
--     position, level (its sides along x and z): a ceiling panel. With w only, a w×w
--     square. n (samples per side) defaults to glint's 4. Some tracers read the two
--     numbers as a radius and a sample count; there, write gr.area_light instead.
-- gr.disc_light(position, colour, falloff, normal, radius)  a disc of that radius facing
--     along normal, as a square of the same area (side radius·√π) perpendicular to it:
--     the same penumbra widths, near enough, with square corners at their very edge.
-- gr.sphericallight(position, colour, falloff, radius)  a ball of that radius, as three
--     mutually perpendicular squares through its centre (each with a third of the colour,
--     sides radius·√π): from any direction the samples spread about as wide as the ball,
--     so shadows soften alike on every side (one square would give shadows sharp along
--     its edge-on direction). It counts as three lights in gr.render's list; this prelude
--     wraps gr.render to unpack it there.

local builtin_render = gr.render
local SQRT_PI = math.sqrt(math.pi)

local checks = require('checks')
local fail, want_positive, want_vec3, cross =
  checks.fail, checks.want_positive, checks.want_vec3, checks.cross

local function scaled(v, s)
  local len = math.sqrt(v[1] * v[1] + v[2] * v[2] + v[3] * v[3])
  return {v[1] * s / len, v[2] * s / len, v[3] * s / len}
end

function gr.arealight(position, colour, falloff, w, h, n)
  want_positive('gr.arealight', 4, 'width', w)
  if h == nil then h = w end
  want_positive('gr.arealight', 5, 'height', h)
  return gr.area_light(position, {w, 0, 0}, {0, 0, h}, colour, falloff, n)
end

function gr.disc_light(position, colour, falloff, normal, radius)
  want_vec3('gr.disc_light', 4, 'normal', normal)
  want_positive('gr.disc_light', 5, 'radius', radius)
  local len = math.sqrt(normal[1] ^ 2 + normal[2] ^ 2 + normal[3] ^ 2)
  if not (len > 0) then fail('gr.disc_light', 4, 'normal', 'a non-zero direction', normal) end
  -- Any two directions across the normal: the least aligned world axis, crossed.
  local helper = math.abs(normal[1]) < 0.5 * len and {1, 0, 0} or {0, 1, 0}
  local u = cross(normal, helper)
  local v = cross(normal, u)
  local side = radius * SQRT_PI
  return gr.area_light(position, scaled(u, side), scaled(v, side), colour, falloff)
end

-- Lights that stand for several glint lights in gr.render's list.
local compound = setmetatable({}, {__mode = 'k'})

function gr.sphericallight(position, colour, falloff, radius)
  want_vec3('gr.sphericallight', 1, 'position', position)
  want_vec3('gr.sphericallight', 2, 'colour', colour)
  want_positive('gr.sphericallight', 4, 'radius', radius)
  local s = radius * SQRT_PI
  local third = {colour[1] / 3, colour[2] / 3, colour[3] / 3}
  local parts = {
    gr.area_light(position, {s, 0, 0}, {0, s, 0}, third, falloff),
    gr.area_light(position, {0, s, 0}, {0, 0, s}, third, falloff),
    gr.area_light(position, {0, 0, s}, {s, 0, 0}, third, falloff),
  }
  local light = {parts = parts}
  compound[light] = true
  return light
end

function gr.render(root, file, w, h, eye, view, up, fov, ambient, lights, ...)
  if type(lights) == 'table' then
    local flat, unpacked = {}, false
    for _, l in ipairs(lights) do
      if compound[l] then
        unpacked = true
        for _, part in ipairs(l.parts) do flat[#flat + 1] = part end
      else
        flat[#flat + 1] = l
      end
    end
    if unpacked then lights = flat end
  end
  return builtin_render(root, file, w, h, eye, view, up, fov, ambient, lights, ...)
end
