// Stack-based BVH traversal over the flattened binary BVH (children adjacent), visiting the nearer
// child first; analytic scene objects are tested by brute force (they are few debug fixtures).

const BVH_STACK_SIZE: u32 = 64u;

struct HitRecord {
  t: f32,
  primitive: u32,
  u: f32,
  v: f32,
}

fn safe_inverse_direction(d: vec3f) -> vec3f {
  // Avoid 0 * inf = NaN in the slab test for axis-parallel rays.
  let tiny = 1e-30;
  let dd = select(d, select(vec3f(-tiny), vec3f(tiny), d >= vec3f(0.0)), abs(d) < vec3f(tiny));
  return 1.0 / dd;
}

fn trace_closest(origin: vec3f, direction: vec3f, t_max_in: f32) -> HitRecord {
  var hit = HitRecord(t_max_in, PRIMITIVE_NONE, 0.0, 0.0);
  if (frame.triangleCount > 0u) {
    let inv = safe_inverse_direction(direction);
    var stack: array<u32, BVH_STACK_SIZE>;
    var sp = 0u;
    var node_index = 0u;
    let root = bvhNodes[0];
    if (intersect_aabb(origin, inv, root.boundsMin, root.boundsMax, hit.t) == F32_INF) {
      sp = 0u; node_index = 0xffffffffu;
    }
    loop {
      if (node_index == 0xffffffffu) { break; }
      let node = bvhNodes[node_index];
      if (node.primitiveCount > 0u) {
        for (var i = 0u; i < node.primitiveCount; i++) {
          let tri_index = node.leftOrFirst + i;
          let r = intersect_triangle(origin, direction, triangles[tri_index], hit.t);
          if (r.x > 0.0) {
            hit = HitRecord(r.x, (PRIMITIVE_KIND_TRIANGLE << 30u) | tri_index, r.y, r.z);
          }
        }
        if (sp == 0u) { break; }
        sp -= 1u;
        node_index = stack[sp];
        continue;
      }
      let left = node.leftOrFirst;
      let right = left + 1u;
      let a = bvhNodes[left];
      let b = bvhNodes[right];
      let ta = intersect_aabb(origin, inv, a.boundsMin, a.boundsMax, hit.t);
      let tb = intersect_aabb(origin, inv, b.boundsMin, b.boundsMax, hit.t);
      if (ta == F32_INF && tb == F32_INF) {
        if (sp == 0u) { break; }
        sp -= 1u;
        node_index = stack[sp];
      } else if (ta == F32_INF) {
        node_index = right;
      } else if (tb == F32_INF) {
        node_index = left;
      } else {
        // Nearer child first; the farther one waits on the stack.
        let near = select(right, left, ta <= tb);
        let far = select(left, right, ta <= tb);
        if (sp < BVH_STACK_SIZE) {
          stack[sp] = far;
          sp += 1u;
        }
        node_index = near;
      }
    }
  }
  for (var i = 0u; i < frame.sceneObjectCount; i++) {
    let obj = sceneObjects[i];
    var t = -1.0;
    var kind = PRIMITIVE_KIND_SPHERE;
    if (obj.kind == SCENE_OBJECT_SPHERE) {
      t = intersect_sphere(origin, direction, obj.a, obj.b.x, hit.t);
    } else {
      t = intersect_box(origin, direction, obj.a, obj.b, hit.t);
      kind = PRIMITIVE_KIND_BOX;
    }
    if (t > 0.0) {
      hit = HitRecord(t, (kind << 30u) | i, 0.0, 0.0);
    }
  }
  if (hit.primitive == PRIMITIVE_NONE) { hit.t = -1.0; }
  return hit;
}

// Any hit within t_max: shadow rays stop at the first occluder.
fn trace_any(origin: vec3f, direction: vec3f, t_max: f32) -> bool {
  if (frame.triangleCount > 0u) {
    let inv = safe_inverse_direction(direction);
    var stack: array<u32, BVH_STACK_SIZE>;
    var sp = 0u;
    stack[0] = 0u;
    sp = 1u;
    loop {
      if (sp == 0u) { break; }
      sp -= 1u;
      let node = bvhNodes[stack[sp]];
      if (intersect_aabb(origin, inv, node.boundsMin, node.boundsMax, t_max) == F32_INF) { continue; }
      if (node.primitiveCount > 0u) {
        for (var i = 0u; i < node.primitiveCount; i++) {
          let r = intersect_triangle(origin, direction, triangles[node.leftOrFirst + i], t_max);
          if (r.x > 0.0) { return true; }
        }
      } else if (sp + 2u <= BVH_STACK_SIZE) {
        stack[sp] = node.leftOrFirst + 1u;
        stack[sp + 1u] = node.leftOrFirst;
        sp += 2u;
      }
    }
  }
  for (var i = 0u; i < frame.sceneObjectCount; i++) {
    let obj = sceneObjects[i];
    var t = -1.0;
    if (obj.kind == SCENE_OBJECT_SPHERE) {
      t = intersect_sphere(origin, direction, obj.a, obj.b.x, t_max);
    } else {
      t = intersect_box(origin, direction, obj.a, obj.b, t_max);
    }
    if (t > 0.0) { return true; }
  }
  return false;
}
