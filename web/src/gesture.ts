// Drag gestures: the edits of one drag share a number, so the server makes them one undo step.

/** A fresh non-zero drag number (random, so two tabs on one drawing do not collide). */
export function newDragId(): number {
  return 1 + Math.floor(Math.random() * 0x7ffffffe);
}
