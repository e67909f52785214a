/**
 * The shape of JSON text before JSON.parse builds it: how many values it holds and how deeply they
 * nest, from one pass over the UTF-8 bytes (RFC 8259 section 2 structural characters, outside
 * strings). Parsing allocates per value, far more than the text's bytes for `[{},{},...]`, and
 * code that walks the result recursively (JSON.stringify, structuredClone, validators) overflows the
 * stack on deep nesting; the loaders refuse both before parsing.
 */

export interface JsonShape {
  /** Arrays, objects and the values separated by commas or colons (an upper estimate of values). */
  values: number;
  /** Deepest nesting of arrays and objects. */
  depth: number;
}

/** Nesting deeper than any real glTF or scene file (their schemas nest about 10 levels). */
export const MAX_JSON_DEPTH = 256;

/** Bytes a parsed JSON value may take in a JavaScript heap (V8 objects and boxed numbers), an upper estimate. */
export const JSON_BYTES_PER_VALUE = 64;

/** Scans UTF-8 bytes or a string (the structural characters are ASCII in both). */
export function scanJson(text: Uint8Array | string): JsonShape {
  const bytes = typeof text === 'string' ? { length: text.length, at: (i: number) => text.charCodeAt(i) } : { length: text.length, at: (i: number) => text[i]! };
  let values = 1;
  let depth = 0;
  let deepest = 0;
  let inString = false;
  for (let i = 0; i < bytes.length; i++) {
    const b = bytes.at(i);
    if (inString) {
      if (b === 0x5c) i++; // backslash: skip the escaped character
      else if (b === 0x22) inString = false;
      continue;
    }
    switch (b) {
      case 0x22: // "
        inString = true;
        break;
      case 0x5b: // [
      case 0x7b: // {
        values++;
        if (++depth > deepest) deepest = depth;
        break;
      case 0x5d: // ]
      case 0x7d: // }
        depth--;
        break;
      case 0x2c: // ,
      case 0x3a: // :
        values++;
        break;
    }
  }
  return { values, depth: deepest };
}
