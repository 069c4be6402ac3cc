// What both setup passes (setup.comp, the classic pipeline; ray_setup.comp, the nonlinear
// projections) share: the source triangle's context (material, cull, shading, its vertices'
// attributes, the world face normal) and the shading record's per-corner half (the CPU's
// setupShadeCorners in src/render/setup.cpp: normals, lit colours, UVs). Needs common.glsl,
// records.glsl and shading.glsl.

// A clipped vertex: its clip-space position and its weights over the source triangle's three
// vertices (the CPU carries the attributes themselves; the weights give the same values).
struct ClipVertex {
  vec4 position;
  vec3 weights;
};

// What setup needs about the source triangle beyond its clip-space vertices.
struct TriangleContext {
  uint triangle;  // scene triangle index
  uint material;  // index into the material buffer
  uint cull;
  uint shading;
  bool has_uv;
  bool has_color;
  bool tangents;  // kObjectHasTangents
  bool clipped;
  bool mirrored;  // the model's determinant is negative
  vec3 face_normal;  // world space, unnormalized
  vec3 normal[3];    // the source vertices' attributes
  vec3 world[3];     // their world positions
  vec2 uv[3];
  vec2 uv1[3];  // TEXCOORD_1 (set 0 where the mesh has none)
  vec4 color[3];
  vec4 tangent[3];  // kObjectHasTangents: world tangents, w the bitangent's sign
};

vec3 weighted3(vec3 values[3], vec3 w) {
  precise vec3 r = values[0] * w.x + values[1] * w.y + values[2] * w.z;
  return r;
}
vec2 weighted2(vec2 values[3], vec3 w) {
  precise vec2 r = values[0] * w.x + values[1] * w.y + values[2] * w.z;
  return r;
}
vec4 weighted4(vec4 values[3], vec3 w) {
  precise vec4 r = values[0] * w.x + values[1] * w.y + values[2] * w.z;
  return r;
}

// The object holding triangle t: the last one whose triangle_base is <= t.
uint objectOfTriangle(uint t) {
  uint lo = 0u, hi = frame.object_count;
  while (lo < hi) {
    const uint mid = (lo + hi) / 2u;
    if (objects[mid].triangle_base <= t) lo = mid + 1u;
    else hi = mid;
  }
  return lo - 1u;
}

// The context of scene triangle t of `object`, whose object-local vertex numbers are idx.
TriangleContext triangleContext(uint t, GpuObject object, uint idx[3]) {
  TriangleContext ctx;
  ctx.triangle = t;
  ctx.material = objectMaterialIndex(
      object, (object.flags & kObjectHasTriangleMaterials) != 0u ? triangle_materials[t] : 0u);
  ctx.cull = object.cull;
  ctx.shading = object.shading;
  ctx.has_uv = (object.flags & kObjectHasUv) != 0u;
  ctx.has_color = (object.flags & kObjectHasColor) != 0u;
  ctx.tangents = (object.flags & kObjectHasTangents) != 0u;
  ctx.mirrored = object.winding_sign < 0.0;
  vec3 p[3];
  for (int k = 0; k < 3; ++k) {
    const uint g = object.vertex_base + idx[k];
    ctx.normal[k] = transformed[g].normal;
    ctx.uv[k] = ctx.has_uv ? vertexUv(g) : vec2(0.0);
    ctx.uv1[k] = ctx.has_uv ? vertexUv1(g) : vec2(0.0);
    ctx.color[k] = ctx.has_color ? vertexColor(g) : vec4(1.0);
    p[k] = vertexPosition(g);
    ctx.world[k] = worldPosition(object.model, p[k]);
    ctx.tangent[k] = vec4(0.0);
    if ((object.flags & kObjectHasTangents) != 0u) {
      // A direction: the model's upper 3x3 (the CPU's model * float4(t, 0)); a mirroring model
      // flips the bitangent.
      const vec4 t = vertexTangent(g);
      precise vec3 world_t = object.model[0].xyz * t.x + object.model[1].xyz * t.y +
                             object.model[2].xyz * t.z;
      precise float w = t.w * object.winding_sign;
      ctx.tangent[k] = vec4(world_t, w);
    }
  }
  precise vec3 e1 = p[1] - p[0];
  precise vec3 e2 = p[2] - p[0];
  precise vec3 edge_cross = vec3(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z,
                                 e1.x * e2.y - e1.y * e2.x);
  precise vec3 face_normal = multiply3x3(object.normal_matrix, edge_cross) * object.winding_sign;
  ctx.face_normal = face_normal;
  return ctx;
}

// The shading record's corners: rasterizer corner k is source vertex order[k]; v[k].weights give
// a clipped vertex's attributes. Leaves the barycentric planes as they are.
void setupShadeCorners(TriangleContext ctx, ClipVertex v[3], int order[3], bool back_facing,
                       inout ShadeRecord shade) {
  const GpuMaterial material = materials[ctx.material];
  const vec3 base = material.base_color.xyz;
  // Back faces that are drawn are lit from the viewer's side (two-sided lighting).
  const float flip = back_facing ? -1.0 : 1.0;
  precise vec3 flat_normal = normalizeAsCpu(ctx.face_normal) * flip;
  // The corners' world positions (a clipped piece's own corners); flat faces are lit at the
  // centroid, as the CPU does.
  vec3 world[3];
  for (int k = 0; k < 3; ++k)
    world[k] = ctx.clipped ? weighted3(ctx.world, v[k].weights) : ctx.world[k];
  precise vec3 centre = (world[0] + world[1] + world[2]) * (1.0 / 3.0);
  const vec3 flat_irradiance =
      ctx.shading == kShadingFlat ? irradiance(flat_normal, centre) : vec3(1.0);
  // The vertex normals face the viewer where the face does, unless a mirroring model's mesh (not
  // turned inside out) has them on the other side of the face than its winding (the CPU's
  // setupShadeCorners: normal_flip).
  float normal_flip = flip;
  if (ctx.mirrored) {
    vec3 sum = vec3(0.0);
    for (int k = 0; k < 3; ++k)
      sum += normalizeAsCpu(ctx.clipped ? weighted3(ctx.normal, v[k].weights) : ctx.normal[k]);
    if (dot(sum, ctx.face_normal) < 0.0) normal_flip = -flip;
  }
  for (int k = 0; k < 3; ++k) {
    const int source = order[k];
    vec3 vertex_normal = ctx.normal[source];
    vec2 uv = ctx.uv[source];
    vec2 uv1 = ctx.uv1[source];
    vec4 color = ctx.color[source];
    if (ctx.clipped) {
      vertex_normal = weighted3(ctx.normal, v[source].weights);
      uv = weighted2(ctx.uv, v[source].weights);
      uv1 = weighted2(ctx.uv1, v[source].weights);
      color = weighted4(ctx.color, v[source].weights);
    }
    precise vec3 n = ctx.shading == kShadingFlat ? flat_normal
                                                 : normalizeAsCpu(vertex_normal) * normal_flip;
    if (n.x == 0.0 && n.y == 0.0 && n.z == 0.0) n = flat_normal;
    shade.normal[k] = vec4(n, world[source].x);
    shade.uv[k] = uv;
    shade.uv1[k] = uv1;
    precise vec3 albedo = ctx.has_color ? base * color.xyz : base;
    precise vec3 lit =
        albedo * (ctx.shading == kShadingGouraud ? irradiance(n, world[source]) : flat_irradiance);
    shade.color[k] = vec4(lit, world[source].y);
    shade.world_z[k] = world[source].z;
    // kPbr: drawn back faces flip the whole tangent frame, as the normal (the CPU's setupShade).
    vec4 tangent = ctx.clipped ? weighted4(ctx.tangent, v[source].weights) : ctx.tangent[source];
    precise vec4 facing_tangent = tangent * normal_flip;
    shade.tangent[k] = facing_tangent;
  }
  shade.triangle_id = ctx.triangle;
  shade.material = ctx.material;
  const bool tangents = ctx.has_uv && ctx.tangents;
  shade.shading =
      ctx.shading |
      (ctx.has_uv && (material.texture_flags & kTexturePresent) != 0u ? kShadeHasUv : 0u) |
      (ctx.shading == kShadingPbr && ctx.has_uv ? kShadePbrUv : 0u) |
      (ctx.shading == kShadingPbr && tangents ? kShadePbrTangents : 0u);
}
