// hit.wgsl — what a traversal returns: the nearest hit.

// The nearest hit: distance, item (a scene grid item: an instance), for triangles the
// barycentric weights of p1 and p2, and part: for a mesh instance the triangle hit (its
// index in `triangles`), for a CSG item the surface hit (leaf instance index, with
// CSG_FLIP when its normal is negated); NO_ITEM otherwise.
// Mirror of src/tracer/traversal/hit.rs::Hit — change both.
struct Hit {
    t: f32,
    item: u32,
    b1: f32,
    b2: f32,
    part: u32,
}

// No hit: t = T_MISS, no item, no part.
// Mirror of src/tracer/traversal/hit.rs::hit_miss — change both.
fn hit_miss() -> Hit {
    return Hit(T_MISS, NO_ITEM, 0.0, 0.0, NO_ITEM);
}

// Mirror of src/tracer/traversal/hit.rs::Hit::is_hit — change both.
fn is_hit(hit: Hit) -> bool {
    return hit.item != NO_ITEM;
}
