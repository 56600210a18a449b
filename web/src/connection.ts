// The WebSocket to the studio server. A message with a payload (the types in WITH_PAYLOAD:
// geometry, mesh, loops, exported) arrives as one binary frame, [JSON length][JSON][payload]
// (see `unpack`); the others as JSON text. Replies carry the id of their request, so
// `request` can await one. The socket reconnects by itself.
import { WITH_PAYLOAD, type ClientMessage, type ServerMessage } from "./protocol";

export interface Handlers {
  /** Every server message, with its payload (null for messages without one). */
  message(msg: ServerMessage, binary: ArrayBuffer | null): void;
  /** The socket (re)opened; `again` is false the first time. */
  opened(again: boolean): void;
  closed(): void;
}

/** A reply to a request: the message and its payload (null for messages without one). */
export interface Reply {
  msg: ServerMessage;
  binary: ArrayBuffer | null;
}

export class Connection {
  private ws!: WebSocket;
  private nextId = 1;
  private waiting = new Map<number, { resolve(r: Reply): void; reject(e: Error): void }>();
  private everOpened = false;
  private retryMs = 250;
  /** performance.now() of the last send, per id (for latency measurements). */
  readonly sentAt = new Map<number, number>();
  /** The timeStamp of the user input a message was sent for, per id, where one was given. */
  readonly inputAt = new Map<number, number>();

  constructor(private url: string, private handlers: Handlers) {
    this.connect();
  }

  get isOpen(): boolean {
    return this.ws.readyState === WebSocket.OPEN;
  }

  private connect(): void {
    this.ws = new WebSocket(this.url);
    this.ws.binaryType = "arraybuffer";
    this.ws.onmessage = (ev) => this.receive(ev.data as string | ArrayBuffer);
    this.ws.onopen = () => {
      const again = this.everOpened;
      this.everOpened = true;
      this.retryMs = 250;
      this.handlers.opened(again);
    };
    this.ws.onclose = () => {
      for (const w of this.waiting.values()) w.reject(new Error("disconnected from the studio server"));
      this.waiting.clear();
      this.handlers.closed();
      setTimeout(() => this.connect(), this.retryMs);
      this.retryMs = Math.min(4000, this.retryMs * 2);
    };
  }

  /** Send a message (its id is filled in) and return the id the reply will carry. `input`: the
   * timeStamp of the pointer or key event it answers (kept for the latency measurements). */
  send(msg: ClientMessage, input = 0): number {
    const id = this.nextId++;
    const text = JSON.stringify({ ...msg, id });
    this.sentAt.set(id, performance.now());
    if (this.sentAt.size > 256) this.sentAt.delete(this.sentAt.keys().next().value as number);
    if (input) {
      this.inputAt.set(id, input);
      if (this.inputAt.size > 256) this.inputAt.delete(this.inputAt.keys().next().value as number);
    }
    if (this.ws.readyState === WebSocket.OPEN) this.ws.send(text);
    else this.ws.addEventListener("open", () => this.ws.send(text), { once: true });
    return id;
  }

  /** Send and await the reply with the same id; an `error` reply rejects with its message. */
  request(msg: ClientMessage, input = 0): Promise<Reply> {
    return new Promise((resolve, reject) => {
      const id = this.send(msg, input);
      this.waiting.set(id, { resolve, reject });
    });
  }

  private receive(data: string | ArrayBuffer): void {
    if (typeof data === "string") {
      this.deliver(JSON.parse(data) as ServerMessage, null);
      return;
    }
    const { msg, payload } = unpack(data);
    if (!WITH_PAYLOAD.includes(msg.type)) console.warn(`studio: ${msg.type} came with a payload`);
    this.deliver(msg, payload);
  }

  private deliver(msg: ServerMessage, binary: ArrayBuffer | null): void {
    this.handlers.message(msg, binary);
    const w = msg.id ? this.waiting.get(msg.id) : undefined;
    if (!w) return;
    this.waiting.delete(msg.id);
    if (msg.type === "error") w.reject(new Error(msg.message));
    else w.resolve({ msg, binary });
  }
}

/** The studio's WebSocket URL on the page's own host. */
export function socketUrl(loc: Location): string {
  return `${loc.protocol === "https:" ? "wss" : "ws"}://${loc.host}/ws`;
}

/** The message and the payload of a binary frame: its first 4 bytes are the JSON's length n
 * (uint32 little-endian, a multiple of 4: the JSON is padded with spaces), then the JSON, then
 * the payload, which thus starts 4-byte aligned. The payload is copied into its own
 * ArrayBuffer, so Float32Array and Uint32Array views of it start at offset 0. */
export function unpack(frame: ArrayBuffer): { msg: ServerMessage; payload: ArrayBuffer } {
  if (frame.byteLength < 4) throw new Error(`binary frame of ${frame.byteLength} bytes has no header`);
  const n = new DataView(frame).getUint32(0, true);
  if (n % 4 !== 0 || 4 + n > frame.byteLength) {
    throw new Error(`binary frame of ${frame.byteLength} bytes cannot hold a message of ${n} bytes`);
  }
  const msg = JSON.parse(decoder.decode(new Uint8Array(frame, 4, n))) as ServerMessage;
  return { msg, payload: frame.slice(4 + n) };
}

const decoder = new TextDecoder();
