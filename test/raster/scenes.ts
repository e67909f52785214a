// Small procedural meshes for the raster tests.

/** A UV sphere of `radius` with outward normals, uvs and counter-clockwise outer faces. */
export function uvSphere(radius: number, segments: number, rings: number): { positions: number[]; normals: number[]; uvs: number[]; indices: number[] } {
  const positions: number[] = [];
  const normals: number[] = [];
  const uvs: number[] = [];
  const indices: number[] = [];
  for (let r = 0; r <= rings; r++) {
    const theta = (Math.PI * r) / rings;
    for (let s = 0; s <= segments; s++) {
      const phi = (2 * Math.PI * s) / segments;
      const n = [Math.sin(theta) * Math.sin(phi), Math.cos(theta), Math.sin(theta) * Math.cos(phi)];
      normals.push(...n);
      positions.push(...n.map((x) => x * radius));
      uvs.push(s / segments, r / rings);
    }
  }
  const row = segments + 1;
  for (let r = 0; r < rings; r++) {
    for (let s = 0; s < segments; s++) {
      const a = r * row + s;
      indices.push(a, a + row, a + 1, a + 1, a + row, a + row + 1);
    }
  }
  return { positions, normals, uvs, indices };
}

/** A quad in the plane z = 0 facing +z, [-h, h]^2, uv (0, 0) at the top-left. */
export function quad(h: number): { positions: number[]; normals: number[]; uvs: number[]; indices: number[] } {
  return {
    positions: [-h, -h, 0, h, -h, 0, h, h, 0, -h, h, 0],
    normals: [0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1],
    uvs: [0, 1, 1, 1, 1, 0, 0, 0],
    indices: [0, 1, 2, 0, 2, 3],
  };
}
