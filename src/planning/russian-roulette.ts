/**
 * Russian roulette survival probability as the render plan's termination policy states it
 * (pbrt-v4 `PathIntegrator::Li`): below `startDepth` every path survives; afterwards a path
 * survives with q = min(1, max component of throughput * etaScale), etaScale undoing the radiance
 * scaling of refraction so that paths inside glass are not killed for it. Survivors divide their
 * throughput by q, which keeps the estimator unbiased.
 */
export function russianRouletteSurvivalProbability(throughput: readonly number[], etaScale: number, depth: number, startDepth: number): number {
  if (depth < startDepth) return 1;
  const m = Math.max(...throughput.map((c) => c * etaScale));
  return Number.isFinite(m) ? Math.min(1, Math.max(0, m)) : 0;
}
