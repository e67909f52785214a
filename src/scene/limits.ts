/**
 * Magnitudes the renderer accepts, so that finite inputs cannot overflow float32 arithmetic on the
 * GPU into Inf or NaN (which would otherwise surface as invalid samples or non-finite pixels far
 * from their cause). Inputs beyond them get a typed error naming the field.
 */

/** Coordinates: squared distances and cross products stay finite in float32 (1e18^2 < 3.4e38). */
export const maxCoordinateMagnitude = 1e18;

/**
 * Emitted and environment radiance per channel: the film sums float32 contributions of many samples
 * (path weights and 1 / pdf factors multiply radiance), so radiance keeps 18 orders of magnitude of
 * headroom below float32's maximum (3.4e38).
 */
export const maxRadiance = 1e20;

/**
 * Emitted power of a scene (sum of area x luminance x pi over its emitters): next-event estimation
 * divides a light's radiance by its pdf, which carries the light's area and the total power, so
 * this keeps those float32 quotients far from overflow.
 */
export const maxEmittedPower = 1e30;
