-- Dialect prelude: constructive solid geometry by operation name, as many CS488
-- tracers wrote it.
--
--   glint render scene.lua --prelude scenes/dialects/csg.lua
--
-- The meaning assumed [glint's gr.csg(name, op, a, b)]:
--
-- gr.union(name, a, b)         in a or in b               [gr.csg(name, 'u', a, b)]
-- gr.intersection(name, a, b)  in both                    [gr.csg(name, 'i', a, b)]
-- gr.intersect(name, a, b)     the same as gr.intersection
-- gr.difference(name, a, b)    in a but not in b          [gr.csg(name, 'd', a, b)]
--
-- The name may be left out (gr.union(a, b)): the node is then named after the operation.
-- Operands are what glint's CSG takes: primitives (sphere, cube, nh_sphere, nh_box,
-- cylinder, cone, torus) or CSG nodes, each with its own transforms; a transform node
-- with the solid as its child is refused (glint's CSG solids are single primitives, and
-- a group's children are not one solid), so a scene that rotates an operand through a
-- parent node needs the rotation on the operand itself. Forms that make an empty node and
-- add the operands later (gr.difference('d'), d:add_children(a, b)) are not read.

local function csg_call(call, op)
  return function(name, a, b, ...)
    if type(name) ~= 'string' then
      -- gr.union(a, b): no name.
      name, a, b = call, name, a
    elseif a == nil then
      error(string.format("gr.%s: this prelude (csg.lua) reads gr.%s(name, a, b) or "
        .. "gr.%s(a, b), with both operands", call, call, call), 2)
    end
    return gr.csg(name, op, a, b)
  end
end

gr.union = csg_call('union', 'u')
gr.intersection = csg_call('intersection', 'i')
gr.intersect = csg_call('intersect', 'i')
gr.difference = csg_call('difference', 'd')
