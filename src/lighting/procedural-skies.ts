import type { Vec3 } from './vec3.ts';

/**
 * Skies without a sun disc, as radiance functions of direction (+Y up), baked to equirect maps by
 * environment-lighting.ts.
 */

/**
 * CIE standard overcast sky (Moon and Spencer 1942; CIE S 011/E:2003 type 16):
 * L(theta) = L_z (1 + 2 cos theta) / 3 above the horizon, neutral in colour. Its horizontal
 * illuminance is E_h = 7 pi L_z / 9.
 */
export function cieOvercastRadiance(zenithLuminance: number, d: readonly number[]): Vec3 {
  const l = (zenithLuminance * (1 + 2 * Math.max(0, d[1]!))) / 3;
  return [l, l, l];
}

export const CIE_OVERCAST_ILLUMINANCE_FACTOR = (7 * Math.PI) / 9;

/** One rectangular softbox of the studio dome, in angular coordinates. */
export interface StudioSoftbox {
  /** Azimuth of the centre, degrees: atan2(z, x) of the direction towards it. */
  azimuthDegrees: number;
  /** Elevation of the centre above the horizon, degrees. */
  elevationDegrees: number;
  /** Full angular width (azimuth) and height (elevation), degrees. */
  widthDegrees: number;
  heightDegrees: number;
  /** Luminance, cd/m^2 (neutral white). */
  luminance: number;
}

/**
 * The 'studio' preset: a neutral photographic studio dome. A dim vertical gradient (a grey
 * cyclorama: 20 nits at the zenith down to 6 nits at the horizon, 3 nits below) and three
 * rectangular softboxes: a large key front-left, a weaker fill front-right, and a long strip light
 * behind and above as a rim. All neutral (equal RGB), so products keep their colours.
 */
export const STUDIO_SOFTBOXES: readonly StudioSoftbox[] = [
  { azimuthDegrees: 135, elevationDegrees: 30, widthDegrees: 40, heightDegrees: 30, luminance: 2000 },
  { azimuthDegrees: 45, elevationDegrees: 20, widthDegrees: 50, heightDegrees: 35, luminance: 500 },
  { azimuthDegrees: 270, elevationDegrees: 55, widthDegrees: 16, heightDegrees: 60, luminance: 1500 },
];

export function studioRadiance(d: readonly number[]): Vec3 {
  const y = Math.max(-1, Math.min(1, d[1]!));
  const elevation = (Math.asin(y) * 180) / Math.PI;
  const azimuth = ((Math.atan2(d[2]!, d[0]!) * 180) / Math.PI + 360) % 360;
  let l = y >= 0 ? 6 + 14 * y : 3;
  for (const box of STUDIO_SOFTBOXES) {
    let da = Math.abs(azimuth - box.azimuthDegrees) % 360;
    if (da > 180) da = 360 - da;
    if (da <= box.widthDegrees / 2 && Math.abs(elevation - box.elevationDegrees) <= box.heightDegrees / 2) l = box.luminance;
  }
  return [l, l, l];
}
