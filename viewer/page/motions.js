// The program's motions as view.json gives them: per motion its source line and
// class, and the poses (x y z i j k) at the start of the program and at each
// motion's end.

// The pose after motion k (k = 0: the start), clamped to the program.
export function cutterPose(motions, k) {
  const index = Math.max(0, Math.min(motions.count, Math.round(k)));
  const p = motions.pose.slice(6 * index, 6 * index + 6);
  return {
    index,
    position: p.slice(0, 3),
    axis: p.slice(3, 6),
    line: index > 0 ? motions.line[index - 1] : null,
    kind: index > 0 ? motions.kind[index - 1] : null,
  };
}

// The slider position (1-based motion) of the last motion commanded by `line`, or -1.
export function motionOfLine(motions, line) {
  return motions.line.lastIndexOf(line) + 1 || -1;
}
