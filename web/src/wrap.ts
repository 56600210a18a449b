// Text wrapping for SVG labels, which do not wrap by themselves.

/** Words of `text` in lines of at most `perLine` characters (a longer word stands alone). */
export function wrapWords(text: string, perLine: number): string[] {
  const lines: string[] = [];
  let line = "";
  for (const word of text.split(" ")) {
    if (line && line.length + 1 + word.length > perLine) {
      lines.push(line);
      line = word;
    } else line = line ? `${line} ${word}` : word;
  }
  if (line) lines.push(line);
  return lines;
}
