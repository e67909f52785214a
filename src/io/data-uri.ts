/**
 * Data URIs (RFC 2397): `data:[<mediatype>][;base64],<data>`. The payload is base64 (RFC 4648
 * section 4, whitespace ignored, padding optional) or percent-encoded bytes. Malformed input is
 * reported, never thrown as a platform exception (atob's InvalidCharacterError).
 */

export type DataUriResult = { bytes: Uint8Array } | { error: string };

const BASE64 = /^[A-Za-z0-9+/]*$/;

/** Decodes `uri`; `maxBytes` caps the decoded size before anything is allocated. */
export function decodeDataUri(uri: string, maxBytes = Infinity): DataUriResult {
  const comma = uri.indexOf(',');
  if (!/^data:/i.test(uri) || comma < 0) return { error: 'a data URI needs "data:" and a comma before its payload' };
  const meta = uri.slice(5, comma);
  const payload = uri.slice(comma + 1);
  if (/;base64$/i.test(meta)) {
    const clean = payload.replace(/[\t\n\f\r ]+/g, '');
    const body = clean.replace(/={1,2}$/, '');
    // A base64 quantum of 4 characters carries 3 bytes; a final group of 1 character carries none.
    if (!BASE64.test(body)) return { error: 'the base64 payload has characters outside A-Z, a-z, 0-9, "+" and "/"' };
    if (body.length % 4 === 1) return { error: `the base64 payload has ${body.length} characters; a length of 4n + 1 is not base64` };
    if (clean.length !== body.length && clean.length % 4 !== 0) return { error: 'the base64 padding does not complete a 4-character group' };
    const size = Math.floor((body.length * 3) / 4);
    if (size > maxBytes) return { error: `${size} decoded bytes exceed the resource limit of ${maxBytes} bytes` };
    const padded = body + '='.repeat((4 - (body.length % 4)) % 4);
    let binary: string;
    try {
      binary = atob(padded);
    } catch (error) {
      return { error: `the base64 payload does not decode (${(error as Error).message})` };
    }
    const bytes = new Uint8Array(binary.length);
    for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
    return { bytes };
  }
  // Percent-encoded: each %XX is one byte, every other character its UTF-8 encoding.
  const encoder = new TextEncoder();
  const out: number[] = [];
  for (let i = 0; i < payload.length; ) {
    if (out.length > maxBytes) return { error: `the payload exceeds the resource limit of ${maxBytes} bytes` };
    if (payload[i] === '%') {
      const hex = payload.slice(i + 1, i + 3);
      if (!/^[0-9A-Fa-f]{2}$/.test(hex)) return { error: `malformed percent escape at character ${i} of the payload` };
      out.push(Number.parseInt(hex, 16));
      i += 3;
    } else {
      const next = payload.indexOf('%', i);
      const end = next < 0 ? payload.length : next;
      for (const b of encoder.encode(payload.slice(i, end))) out.push(b);
      i = end;
    }
  }
  if (out.length > maxBytes) return { error: `${out.length} decoded bytes exceed the resource limit of ${maxBytes} bytes` };
  return { bytes: Uint8Array.from(out) };
}
