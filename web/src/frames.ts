// Work that only changes what is on screen runs once per animation frame, however many
// store events asked for it: a panel redraws at most once a frame during a drag, and the
// message handler that delivers new geometry returns sooner.

/** A function that schedules `fn` for the next animation frame (once, however often called). */
export function perFrame(fn: () => void): () => void {
  let frame = 0;
  return () => {
    if (!frame) frame = requestAnimationFrame(() => { frame = 0; fn(); });
  };
}
