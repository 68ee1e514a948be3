// What a PNG shows, decoded by the browser of a playwright page (no image library):
// its size, the standard deviation of its grey level, and the shares of its pixels
// that are drawn (neither the viewer's background nor white), not near white (any
// channel below 235) and coloured (channels apart by more than 60).
export const pngStats = (page, src) => page.evaluate(async (src) => {
  const img = new Image();
  img.src = src;
  await img.decode();
  const c = document.createElement('canvas');
  [c.width, c.height] = [img.width, img.height];
  const g = c.getContext('2d');
  g.drawImage(img, 0, 0);
  const d = g.getImageData(0, 0, c.width, c.height).data;
  let [sum, sq, drawn, dark, hues] = [0, 0, 0, 0, 0];
  for (let k = 0; k < d.length; k += 4) {
    const y = 0.299 * d[k] + 0.587 * d[k + 1] + 0.114 * d[k + 2];
    sum += y;
    sq += y * y;
    if (Math.abs(d[k] - 244) + Math.abs(d[k + 1] - 245) + Math.abs(d[k + 2] - 247) > 24 && y < 250) drawn += 1;
    if (d[k] < 235 || d[k + 1] < 235 || d[k + 2] < 235) dark += 1;
    if (Math.max(d[k], d[k + 1], d[k + 2]) - Math.min(d[k], d[k + 1], d[k + 2]) > 60) hues += 1;
  }
  const n = d.length / 4;
  return {
    width: c.width,
    height: c.height,
    sd: Math.sqrt(sq / n - (sum / n) ** 2),
    drawn: drawn / n,
    notWhite: dark / n,
    coloured: hues / n,
  };
}, src);
