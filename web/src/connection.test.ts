import { describe, expect, it } from "vitest";
import { unpack } from "./connection";

/** A frame laid out by hand: uint32 LE length, JSON padded with spaces to 4 bytes, payload. */
function frame(json: string, payload: number[]): ArrayBuffer {
  const head = new TextEncoder().encode(json);
  const n = Math.ceil(head.length / 4) * 4;
  const buf = new ArrayBuffer(4 + n + 4 * payload.length);
  new DataView(buf).setUint32(0, n, true);
  const bytes = new Uint8Array(buf);
  bytes.fill(0x20, 4, 4 + n);
  bytes.set(head, 4);
  payload.forEach((v, i) => new DataView(buf).setFloat32(4 + n + 4 * i, v, true));
  return buf;
}

describe("unpack", () => {
  it("splits the message from its payload, which starts at offset 0 of its own buffer", () => {
    const { msg, payload } = unpack(frame('{"type":"geometry","id":7}', [1.5, -2, 3.25]));
    expect(msg).toMatchObject({ type: "geometry", id: 7 });
    expect(payload.byteLength).toBe(12);
    expect(Array.from(new Float32Array(payload))).toEqual([1.5, -2, 3.25]);
  });

  it("reads non-ASCII JSON by its byte length", () => {
    const { msg, payload } = unpack(frame('{"type":"exported","name":"Maßwerk.glb"}', [0]));
    expect((msg as { name: string }).name).toBe("Maßwerk.glb");
    expect(payload.byteLength).toBe(4);
  });

  it("refuses frames shorter than their header says", () => {
    expect(() => unpack(new ArrayBuffer(2))).toThrow("has no header");
    const bad = frame("{}", []);
    new DataView(bad).setUint32(0, 8, true);
    expect(() => unpack(bad)).toThrow("cannot hold a message of 8 bytes");
  });
});
