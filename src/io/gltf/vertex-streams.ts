/** A primitive's triangle-list geometry as float32 vertex streams (the renderer's mesh layout). */
export interface VertexStreams {
  positions: Float32Array;
  indices: Uint32Array;
  normals?: Float32Array;
  tangents?: Float32Array;
  uvs?: Float32Array;
  uvs1?: Float32Array;
  /** rgb or rgba per vertex. */
  colors?: Float32Array;
}
