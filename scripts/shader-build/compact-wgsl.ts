// The linked programs ship without comments and indentation: the comments are for readers of the
// .wesl sources, and the shader text is most of the package's code in a browser bundle (about 30%
// smaller this way). WGSL has no string literals, so `//` always starts a line comment; block
// comments nest (WGSL spec, section 3.2 "Comments").

/** `wgsl` without comments, leading and trailing blanks, or empty lines. */
export function compactWgsl(wgsl: string): string {
  let out = '';
  let depth = 0;
  for (let i = 0; i < wgsl.length; i++) {
    const two = wgsl.slice(i, i + 2);
    if (two === '/*') {
      depth++;
      i++;
    } else if (depth > 0) {
      if (two === '*/') {
        depth--;
        i++;
      } else if (wgsl[i] === '\n') out += '\n';
    } else if (two === '//') {
      while (i < wgsl.length && wgsl[i] !== '\n') i++;
      i--;
    } else out += wgsl[i];
  }
  return out
    .split('\n')
    .map((line) => line.trim())
    .filter((line) => line !== '')
    .join('\n');
}
