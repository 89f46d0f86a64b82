-- Argument checks and vector helpers that the dialect preludes share (lights.lua,
-- nh-shapes.lua, planes.lua `require` it from beside themselves; it is not a prelude and
-- defines no gr call). A check that fails raises its error at level 3: the caller of the
-- check's caller, as when each prelude defined these itself.

local checks = {}

function checks.is_vec3(v)
  return type(v) == 'table' and type(v[1]) == 'number' and type(v[2]) == 'number'
    and type(v[3]) == 'number'
end

function checks.fail(call, n, name, what, got)
  local shown = type(got) == 'string' and ("'" .. got .. "'") or type(got)
  error(string.format('%s: argument %d (%s) must be %s, got %s', call, n, name, what, shown),
    3)
end

function checks.want_positive(call, n, name, v)
  if type(v) ~= 'number' or not (v > 0) then
    checks.fail(call, n, name, 'a positive number', v)
  end
end

function checks.want_vec3(call, n, name, v)
  if not checks.is_vec3(v) then checks.fail(call, n, name, 'a table of 3 numbers {x, y, z}', v) end
end

function checks.cross(a, b)
  return {a[2] * b[3] - a[3] * b[2], a[3] * b[1] - a[1] * b[3], a[1] * b[2] - a[2] * b[1]}
end

return checks
