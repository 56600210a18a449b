import { describe, expect, it } from "vitest";
import { DragSender } from "./dragsender";

/** A sender whose requests and frames the test resolves by hand. */
function rig(key?: (m: { k: string; v: number }) => string) {
  const sent: { msg: { k: string; v: number }; input: number; done: () => void }[] = [];
  const frames: (() => void)[] = [];
  let idles = 0;
  const s = new DragSender<{ k: string; v: number }>({
    request: (msg, input) => new Promise<void>((done) => sent.push({ msg, input, done })),
    key, idle: () => { idles++; }, frame: (fn) => { frames.push(fn); },
  });
  const reply = async () => { sent[sent.length - 1].done(); await Promise.resolve(); await Promise.resolve(); };
  const frame = () => { const f = frames.splice(0); f.forEach((fn) => fn()); };
  return { s, sent, reply, frame, idles: () => idles };
}

describe("DragSender", () => {
  it("sends at once, one in flight, the latest value when the reply is in", async () => {
    const { s, sent, reply, frame, idles } = rig();
    s.push({ k: "a", v: 1 }, 10);
    expect(sent.map((x) => [x.msg.v, x.input])).toEqual([[1, 10]]);
    s.push({ k: "a", v: 2 }, 11);
    s.push({ k: "a", v: 3 }, 12);       // replaces 2 while 1 is in flight
    expect(sent.length).toBe(1);
    frame();                            // a new frame: still waiting for the reply
    await reply();
    expect(sent.map((x) => [x.msg.v, x.input])).toEqual([[1, 10], [3, 12]]);
    expect(s.pending).toBe(true);
    await reply();
    expect(s.pending).toBe(false);
    expect(idles()).toBe(1);
  });

  it("sends at most one edit per frame", async () => {
    const { s, sent, reply, frame } = rig();
    s.push({ k: "a", v: 1 });
    await reply();                      // the reply comes within the same frame
    s.push({ k: "a", v: 2 });
    expect(sent.length).toBe(1);        // waits for the next frame
    frame();
    expect(sent.map((x) => x.msg.v)).toEqual([1, 2]);
  });

  it("keeps one unsent edit per key, in order, and drops a repeat of the last one sent", async () => {
    const { s, sent, reply, frame } = rig((m) => m.k);
    s.push({ k: "a", v: 1 });
    s.push({ k: "b", v: 5 });
    s.push({ k: "b", v: 6 });
    s.push({ k: "a", v: 1 });           // another key after b: queued after it
    frame(); await reply();
    frame(); await reply();
    frame(); await reply();
    expect(sent.map((x) => `${x.msg.k}${x.msg.v}`)).toEqual(["a1", "b6", "a1"]);
    s.push({ k: "a", v: 1 });           // equal to the last one sent: not sent again
    frame();
    expect(sent.length).toBe(3);
    s.begin();                          // a new drag sends it
    s.push({ k: "a", v: 1 });
    expect(sent.length).toBe(4);
  });
});

describe("DragSender idle", () => {
  it("comes when a waiting repeat of the last edit is dropped at the frame", async () => {
    const { s, sent, reply, frame, idles } = rig();
    s.push({ k: "a", v: 1 });
    await reply();                      // within the frame: idle once
    expect(idles()).toBe(1);
    s.push({ k: "a", v: 2 });           // waits for the frame
    s.push({ k: "a", v: 1 });           // replaced by a repeat of the last one sent
    frame();                            // dropped: nothing in flight, nothing waits
    expect(sent.length).toBe(1);
    expect(s.pending).toBe(false);
    expect(idles()).toBeGreaterThanOrEqual(2);
  });
});
