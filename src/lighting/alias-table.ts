/**
 * Walker's alias method with Vose's stable construction ("A Linear Algorithm for Generating Random
 * Numbers with a Given Distribution", IEEE TSE 1991): O(1) sampling of a discrete distribution.
 * Sampling: i = floor(u * n), keep i when frac(u * n) < threshold[i], else take alias[i].
 */
export interface AliasTable {
  threshold: Float64Array;
  alias: Uint32Array;
  /** Normalised probabilities of each entry. */
  pmf: Float64Array;
}

export function buildAliasTable(weights: ArrayLike<number>): AliasTable {
  const n = weights.length;
  if (n === 0) throw new RangeError('alias table needs at least one weight');
  let total = 0;
  for (let i = 0; i < n; i++) {
    const w = weights[i]!;
    if (!(w >= 0) || !Number.isFinite(w)) throw new RangeError(`weight ${i} is not a finite non-negative number`);
    total += w;
  }
  if (!(total > 0)) throw new RangeError('alias table weights sum to zero');
  const pmf = new Float64Array(n);
  const scaled = new Float64Array(n);
  for (let i = 0; i < n; i++) {
    pmf[i] = weights[i]! / total;
    scaled[i] = pmf[i]! * n;
  }
  const threshold = new Float64Array(n);
  const alias = new Uint32Array(n);
  const small: number[] = [];
  const large: number[] = [];
  for (let i = 0; i < n; i++) (scaled[i]! < 1 ? small : large).push(i);
  while (small.length > 0 && large.length > 0) {
    const s = small.pop()!;
    const l = large.pop()!;
    threshold[s] = scaled[s]!;
    alias[s] = l;
    scaled[l] = scaled[l]! + scaled[s]! - 1;
    (scaled[l]! < 1 ? small : large).push(l);
  }
  // Leftovers are 1 up to rounding.
  for (const i of [...small, ...large]) {
    threshold[i] = 1;
    alias[i] = i;
  }
  return { threshold, alias, pmf };
}

/** Probability that sampling the table returns each index (for tests: must equal pmf). */
export function aliasTableDistribution(table: AliasTable): Float64Array {
  const n = table.threshold.length;
  const p = new Float64Array(n);
  for (let i = 0; i < n; i++) {
    p[i] = p[i]! + table.threshold[i]! / n;
    p[table.alias[i]!] = p[table.alias[i]!]! + (1 - table.threshold[i]!) / n;
  }
  return p;
}
