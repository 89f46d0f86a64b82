-- Dialect prelude: planes, quads and discs the way many CS488 tracers wrote them.
--
--   glint render scene.lua --prelude scenes/dialects/planes.lua
--
-- Glint has no plane, quad or disc primitive; these calls make inline meshes (flat, two
-- triangles per quad, UVs as below), which any node method, material and texture takes.
-- The meaning assumed:
--
-- gr.plane(name)                   an "infinite" plane through the origin, normal +y
--                                  (a floor: the way gr.plane scenes mostly use it).
-- gr.plane(name, point, normal)    an "infinite" plane through point, normal `normal`.
-- gr.nh_plane(name)                the unit square [-0.5, 0.5]² in the XY plane, normal
--                                  +z (scenes scale it: a 10×10 wall is scale(10, 10, 1)).
-- gr.nh_plane(name, point, normal[, size])  a square of side `size` centred at point,
--                                  perpendicular to normal; without size, "infinite".
-- gr.nh_sheet(name, centre, w, h)  a w×h rectangle centred at centre in the plane
--                                  z = centre.z, normal +z, w along x, h along y.
-- gr.nh_rect(name, corner, {sx, sy, sz})  a box from corner to corner + size (a cube
--                                  of three sizes: gr.nh_box with a size per axis).
-- gr.nh_rect(name, corner, w, h)   a w×h rectangle from corner along +x and +y, normal +z.
-- gr.disc(name)                    the unit disc (radius 1) in the XY plane, normal +z.
-- gr.disc(name, centre, normal, radius)  a disc of that radius centred at centre.
--
-- "Infinite": glint bounds every object (its grid needs bounds), so an infinite plane is
-- a finite one far bigger than any CS488 scene: a square of half-side 2^17 = 131 072
-- units (before the node's transforms), seen from a camera 100 units above it ending
-- 0.04° below the horizon (a fraction of a pixel). It is built of nested rings, each 16
-- times the size of the one inside it (from a centre square of half-side 1/8 out), so
-- that the triangles around any point are at most about 16 times that point's distance
-- from the centre: a hit's rounding error stays proportional to where it is, far below
-- glint's scale-free secondary-ray offsets (one pair of huge triangles would make it
-- proportional to the plane's size: shadow acne near the camera). 21 quads in all, so a
-- ray tests few triangles. Rings meet edge to edge (no T-junctions), so the watertight
-- triangle test leaves no cracks. The UVs of planes are in object units (u along the
-- first in-plane axis, v along the second), so a texture repeats once per unit as most
-- tracers' infinite planes did; those of quads, sheets and rects run from 0 to 1 across
-- them; discs' are planar, (x/r + 1)/2 and (y/r + 1)/2, like glint's cylinder caps. A disc is a 128-sided polygon (its rim
-- within 0.03% of the radius of the circle).

local checks = require('checks')
local fail, want_vec3, want_positive, cross =
  checks.fail, checks.want_vec3, checks.want_positive, checks.cross

local function want_name(call, name)
  if type(name) ~= 'string' then fail(call, 1, 'name', 'a string', name) end
end

local function normalise(call, n, v)
  local len = math.sqrt(v[1] * v[1] + v[2] * v[2] + v[3] * v[3])
  if not (len > 0) or len == math.huge then
    fail(call, n, 'normal', 'a non-zero direction', v)
  end
  return {v[1] / len, v[2] / len, v[3] / len}
end

-- Two unit axes (u, v) of the plane with normal n, u × v = n: u from the world axis least
-- along n, so that the frame is the same for the same normal.
local function plane_axes(n)
  local ax, ay, az = math.abs(n[1]), math.abs(n[2]), math.abs(n[3])
  local helper
  if ax <= ay and ax <= az then helper = {1, 0, 0}
  elseif ay <= az then helper = {0, 1, 0}
  else helper = {0, 0, 1} end
  local v = cross(n, helper)
  local len = math.sqrt(v[1] * v[1] + v[2] * v[2] + v[3] * v[3])
  v = {v[1] / len, v[2] / len, v[3] / len}
  return cross(v, n), v
end

-- A flat mesh from polygons given in plane coordinates (a, b) with their UVs: the point
-- is origin + a·u + b·v.
local function flat_mesh(name, origin, u, v, polygons)
  local verts, faces, uvs = {}, {}, {}
  for _, poly in ipairs(polygons) do
    local face = {}
    for _, c in ipairs(poly) do
      local a, b = c[1], c[2]
      verts[#verts + 1] = {origin[1] + a * u[1] + b * v[1], origin[2] + a * u[2] + b * v[2],
        origin[3] + a * u[3] + b * v[3]}
      uvs[#uvs + 1] = {c[3], c[4]}
      face[#face + 1] = #verts - 1
    end
    faces[#faces + 1] = face
  end
  return gr.mesh(name, verts, faces, uvs)
end

local INFINITE_HALF_SIDE = 2 ^ 17
local INNER_HALF_SIDE = 2 ^ -3
local RING_GROWTH = 16

-- The "infinite" plane: a centre square and rings of four trapezoids out to 2^17.
local function infinite_plane(name, origin, u, v)
  local polys = {}
  local function corner(a, b) return {a, b, a, b} end
  local h = INNER_HALF_SIDE
  polys[1] = {corner(-h, -h), corner(h, -h), corner(h, h), corner(-h, h)}
  while h < INFINITE_HALF_SIDE do
    local H = RING_GROWTH * h
    -- Counter-clockwise seen from +n, as the centre square.
    polys[#polys + 1] = {corner(-H, -H), corner(H, -H), corner(h, -h), corner(-h, -h)}
    polys[#polys + 1] = {corner(H, -H), corner(H, H), corner(h, h), corner(h, -h)}
    polys[#polys + 1] = {corner(H, H), corner(-H, H), corner(-h, h), corner(h, h)}
    polys[#polys + 1] = {corner(-H, H), corner(-H, -H), corner(-h, -h), corner(-h, h)}
    h = H
  end
  return flat_mesh(name, origin, u, v, polys)
end

-- A rectangle from (a0, b0) to (a1, b1), UVs 0 to 1 across it.
local function rectangle(name, origin, u, v, a0, b0, a1, b1)
  return flat_mesh(name, origin, u, v,
    {{{a0, b0, 0, 0}, {a1, b0, 1, 0}, {a1, b1, 1, 1}, {a0, b1, 0, 1}}})
end

local X, Y, Z, ORIGIN = {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}

function gr.plane(name, point, normal, ...)
  want_name('gr.plane', name)
  if point == nil then
    return infinite_plane(name, ORIGIN, X, {0, 0, -1})
  end
  if select('#', ...) > 0 then
    error('gr.plane: this prelude (planes.lua) reads gr.plane(name) or '
      .. 'gr.plane(name, point, normal); for a finite quad use gr.nh_plane(name, point, '
      .. 'normal, size) or gr.nh_sheet', 2)
  end
  want_vec3('gr.plane', 2, 'point', point)
  want_vec3('gr.plane', 3, 'normal', normal)
  local u, v = plane_axes(normalise('gr.plane', 3, normal))
  return infinite_plane(name, point, u, v)
end

function gr.nh_plane(name, point, normal, size)
  want_name('gr.nh_plane', name)
  if point == nil then
    return rectangle(name, ORIGIN, X, Y, -0.5, -0.5, 0.5, 0.5)
  end
  want_vec3('gr.nh_plane', 2, 'point', point)
  want_vec3('gr.nh_plane', 3, 'normal', normal)
  local u, v = plane_axes(normalise('gr.nh_plane', 3, normal))
  if size == nil then return infinite_plane(name, point, u, v) end
  want_positive('gr.nh_plane', 4, 'size', size)
  return rectangle(name, point, u, v, -size / 2, -size / 2, size / 2, size / 2)
end

function gr.nh_sheet(name, centre, w, h)
  want_name('gr.nh_sheet', name)
  want_vec3('gr.nh_sheet', 2, 'centre', centre)
  want_positive('gr.nh_sheet', 3, 'width', w)
  want_positive('gr.nh_sheet', 4, 'height', h)
  return rectangle(name, centre, X, Y, -w / 2, -h / 2, w / 2, h / 2)
end

function gr.nh_rect(name, corner, size, h)
  want_name('gr.nh_rect', name)
  want_vec3('gr.nh_rect', 2, 'corner', corner)
  if type(size) == 'number' then
    want_positive('gr.nh_rect', 3, 'width', size)
    want_positive('gr.nh_rect', 4, 'height', h)
    return rectangle(name, corner, X, Y, 0, 0, size, h)
  end
  want_vec3('gr.nh_rect', 3, 'size', size)
  for i = 1, 3 do want_positive('gr.nh_rect', 3, 'size', size[i]) end
  local box = gr.cube(name)
  box:set_placement(corner, {size[1], 0, 0}, {0, size[2], 0}, {0, 0, size[3]})
  return box
end

local DISC_SIDES = 128

function gr.disc(name, centre, normal, radius)
  want_name('gr.disc', name)
  local u, v, r = X, Y, 1
  if centre == nil then
    centre = ORIGIN
  else
    want_vec3('gr.disc', 2, 'centre', centre)
    want_vec3('gr.disc', 3, 'normal', normal)
    want_positive('gr.disc', 4, 'radius', radius)
    u, v = plane_axes(normalise('gr.disc', 3, normal))
    r = radius
  end
  -- A fan around the centre (no sliver triangles), counter-clockwise seen from +normal.
  local polys = {}
  for i = 0, DISC_SIDES - 1 do
    local t0, t1 = 2 * math.pi * i / DISC_SIDES, 2 * math.pi * (i + 1) / DISC_SIDES
    local c0, s0, c1, s1 = math.cos(t0), math.sin(t0), math.cos(t1), math.sin(t1)
    polys[#polys + 1] = {{0, 0, 0.5, 0.5}, {r * c0, r * s0, (c0 + 1) / 2, (s0 + 1) / 2},
      {r * c1, r * s1, (c1 + 1) / 2, (s1 + 1) / 2}}
  end
  return flat_mesh(name, centre, u, v, polys)
end
