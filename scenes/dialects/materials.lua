-- Dialect prelude: mirrors and glass the way many CS488 tracers wrote them.
--
--   glint render scene.lua --prelude scenes/dialects/materials.lua
--
-- The meaning assumed (glint's own calls in brackets):
--
-- gr.material(kd, ks, p, reflect)             reflect: a number or {r,g,b}; the colour seen
-- gr.material(kd, ks, p, reflect, ior)        along the mirror direction, times reflect, is
-- gr.material(kd, ks, p, reflect, ior, gloss) added to the Phong colour [m:set_reflection].
--     0 (or nil, or false) is no mirror.
--     ior: the index of refraction of a clear solid [m:set_refraction(ior)]. An index of
--     1 or less (0 is the usual "not glass") leaves the material opaque: a solid of index 1
--     in air would be no surface at all, so such scenes mean "not transparent". Glint's
--     glass is clear (no partial transparency, no tint); its Phong terms still add, so a
--     glass ball wants kd {0,0,0}.
--     gloss (blurry reflection), whatever it is, is ignored: glint's mirrors are perfect.
--     A 7th argument or more is refused: forms of 7 and more arguments put different
--     things in the same slots (transparency, index, gloss), and a guess would be wrong
--     for half of them (the message says to use m:set_reflection and m:set_refraction).
-- gr.mirror_material(kd, ks, p[, gloss])      a mirror whose reflected colour is ks (the
--     specular colour: Whitted's weight for the mirror ray) [m:set_reflection(ks)].
-- gr.clear_material(kd, ks, p, gloss, ior)    glass of index ior (any index > 0: a "clear"
--     material of index 1 is invisible but for its highlights, as its author asked).
-- gr.transparent_material(t, r, ior)          numbers: transparency t (0–1), reflectivity r,
--     index ior. Glint's glass is fully clear, so t only tints: kd = (1 − t) grey, ks 0.5,
--     shininess 100, plus r as a mirror term on top of the Fresnel reflection.
-- gr.transparent_material(kd, ks, p, ior[, t]) colours first: glass of index ior with those
--     Phong terms; t is ignored (clear glass).
--
-- Arguments are checked here; a wrong one is reported at the scene's line.

local builtin_material = gr.material

local function is_colour(v)
  return type(v) == 'table' and type(v[1]) == 'number' and type(v[2]) == 'number'
    and type(v[3]) == 'number'
end

local function nonzero(c)
  if type(c) == 'number' then return c ~= 0 end
  return c[1] ~= 0 or c[2] ~= 0 or c[3] ~= 0
end

-- Argument `n` of `call` must be a number or a colour (level 3: the scene's line).
local function check_number_or_colour(call, n, name, v)
  if type(v) ~= 'number' and not is_colour(v) then
    error(string.format('%s: argument %d (%s) must be a number or a colour {r, g, b}, got %s',
      call, n, name, type(v) == 'string' and ("'" .. v .. "'") or type(v)), 3)
  end
end

local function check_number(call, n, name, v)
  if type(v) ~= 'number' then
    error(string.format('%s: argument %d (%s) must be a number, got %s', call, n, name,
      type(v) == 'string' and ("'" .. v .. "'") or type(v)), 3)
  end
end

function gr.material(kd, ks, p, reflect, ior, gloss, ...)
  if type(kd) == 'string' or (reflect == nil and ior == nil and gloss == nil) then
    return builtin_material(kd, ks, p)
  end
  if select('#', ...) > 0 then
    error('gr.material: 7 or more arguments: this prelude (materials.lua) reads only '
      .. 'gr.material(kd, ks, p, reflect, ior, gloss); use m:set_reflection(c) and '
      .. 'm:set_refraction(ior) for the rest', 2)
  end
  local m = builtin_material(kd, ks, p)
  if reflect ~= nil and reflect ~= false then
    check_number_or_colour('gr.material', 4, 'reflect', reflect)
    if nonzero(reflect) then m:set_reflection(reflect) end
  end
  if ior ~= nil and ior ~= false then
    check_number('gr.material', 5, 'ior', ior)
    if ior > 1 then m:set_refraction(ior) end
  end
  return m
end

function gr.mirror_material(kd, ks, p, gloss)
  check_number_or_colour('gr.mirror_material', 2, 'ks', ks)
  local m = builtin_material(kd, ks, p)
  if nonzero(ks) then m:set_reflection(ks) end
  return m
end

function gr.clear_material(kd, ks, p, gloss, ior)
  check_number('gr.clear_material', 5, 'ior', ior)
  if ior <= 0 then
    error(string.format('gr.clear_material: argument 5 (ior) must be a positive index of '
      .. 'refraction, got %s', tostring(ior)), 2)
  end
  local m = builtin_material(kd, ks, p)
  m:set_refraction(ior)
  return m
end

function gr.transparent_material(a, b, c, d, e)
  if type(a) == 'number' then
    local t, r, ior = a, b, c
    check_number('gr.transparent_material', 2, 'reflectivity', r)
    check_number('gr.transparent_material', 3, 'ior', ior)
    local grey = math.max(0, math.min(1, 1 - t))
    local m = builtin_material({grey, grey, grey}, {0.5, 0.5, 0.5}, 100)
    if ior > 0 then m:set_refraction(ior) end
    if r ~= 0 then m:set_reflection(r) end
    return m
  end
  check_number('gr.transparent_material', 4, 'ior', d)
  local m = builtin_material(a, b, c)
  if d > 0 then m:set_refraction(d) end
  return m
end
