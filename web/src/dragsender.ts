// Sending the edits of a drag (a point or handle in the top view, a height in the side view).
// One edit awaits its reply at a time, and at most one goes out per animation frame; each goes
// out as soon as both allow. An unsent edit is replaced by a newer one for the same key (the
// latest position wins), and an edit equal to the last one sent is not sent again.

export interface DragSenderOptions<M> {
  /** Send `msg`; `input` is the timeStamp of the pointer event it answers (0: none). */
  request(msg: M, input: number): Promise<unknown>;
  /** Edits with the same key replace each other while unsent (default: one stream). */
  key?(msg: M): string;
  /** Called whenever nothing is in flight or waiting any more (after a reply, at a frame, or
   * when a repeat of the last edit was dropped); may come more than once. */
  idle?(): void;
  /** Schedules a call at the next animation frame (default requestAnimationFrame). */
  frame?(fn: () => void): void;
}

export class DragSender<M> {
  private queue: { msg: M; key: string; text: string; input: number }[] = [];
  private busy = false;
  private sentThisFrame = false;
  private frameDue = false;
  private last = "";

  constructor(private readonly o: DragSenderOptions<M>) {}

  /** Whether an edit awaits its reply or waits to be sent. */
  get pending(): boolean {
    return this.busy || this.queue.length > 0;
  }

  /** A new drag: its first edit is sent even if it equals the last one sent. */
  begin(): void {
    this.last = "";
  }

  push(msg: M, input = 0): void {
    const key = this.o.key ? this.o.key(msg) : "";
    const item = { msg, key, text: JSON.stringify(msg), input };
    const tail = this.queue[this.queue.length - 1];
    if (tail && tail.key === key) this.queue[this.queue.length - 1] = item;
    else this.queue.push(item);
    this.flush();
    this.settle();
  }

  /** Nothing in flight or waiting (a repeat of the last edit may just have been dropped): idle. */
  private settle(): void {
    if (!this.pending) this.o.idle?.();
  }

  private flush(): void {
    if (this.busy) return;
    while (this.queue.length && this.queue[0].text === this.last) this.queue.shift();
    if (!this.queue.length || this.sentThisFrame) return; // (the frame below sends it)
    const { msg, text, input } = this.queue.shift()!;
    this.last = text;
    this.busy = true;
    this.sentThisFrame = true;
    if (!this.frameDue) {
      this.frameDue = true;
      (this.o.frame ?? requestAnimationFrame)(() => {
        this.frameDue = false;
        this.sentThisFrame = false;
        this.flush();
        this.settle();
      });
    }
    this.o.request(msg, input).catch(() => undefined).finally(() => { // errors are in the status bar
      this.busy = false;
      this.flush();
      this.settle();
    });
  }
}

/** Whether the browser fires pointerrawupdate (Chromium, in secure contexts such as 127.0.0.1):
 * it comes as soon as the mouse moves, while pointermove waits for the next animation frame. */
export const RAW_UPDATES = typeof window !== "undefined" && "onpointerrawupdate" in window;
