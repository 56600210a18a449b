// The WebSocket to the studio server. Messages whose type is in BINARY_FOLLOWS (geometry,
// mesh, loops, exported) are always followed by one binary frame; this pairs them. Replies
// carry the id of their request, so `request` can await one. The socket reconnects by itself.
import { BINARY_FOLLOWS, type ClientMessage, type ServerMessage } from "./protocol";

export interface Handlers {
  /** Every server message, with its binary frame where one follows. */
  message(msg: ServerMessage, binary: ArrayBuffer | null): void;
  /** The socket (re)opened; `again` is false the first time. */
  opened(again: boolean): void;
  closed(): void;
}

/** A reply to a request: the message and its binary frame (null where none follows). */
export interface Reply {
  msg: ServerMessage;
  binary: ArrayBuffer | null;
}

export class Connection {
  private ws!: WebSocket;
  private pending: ServerMessage | null = null;
  private nextId = 1;
  private waiting = new Map<number, { resolve(r: Reply): void; reject(e: Error): void }>();
  private everOpened = false;
  private retryMs = 250;
  /** performance.now() of the last send, per id (for latency measurements). */
  readonly sentAt = new Map<number, number>();

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
      this.pending = null;
      for (const w of this.waiting.values()) w.reject(new Error("disconnected from the studio server"));
      this.waiting.clear();
      this.handlers.closed();
      setTimeout(() => this.connect(), this.retryMs);
      this.retryMs = Math.min(4000, this.retryMs * 2);
    };
  }

  /** Send a message (its id is filled in) and return the id the reply will carry. */
  send(msg: ClientMessage): number {
    const id = this.nextId++;
    const text = JSON.stringify({ ...msg, id });
    this.sentAt.set(id, performance.now());
    if (this.sentAt.size > 256) this.sentAt.delete(this.sentAt.keys().next().value as number);
    if (this.ws.readyState === WebSocket.OPEN) this.ws.send(text);
    else this.ws.addEventListener("open", () => this.ws.send(text), { once: true });
    return id;
  }

  /** Send and await the reply with the same id; an `error` reply rejects with its message. */
  request(msg: ClientMessage): Promise<Reply> {
    return new Promise((resolve, reject) => {
      const id = this.send(msg);
      this.waiting.set(id, { resolve, reject });
    });
  }

  private receive(data: string | ArrayBuffer): void {
    if (typeof data === "string") {
      const msg = JSON.parse(data) as ServerMessage;
      if (BINARY_FOLLOWS.includes(msg.type)) this.pending = msg;
      else this.deliver(msg, null);
      return;
    }
    if (this.pending === null) return; // a binary frame always follows its message
    const msg = this.pending;
    this.pending = null;
    this.deliver(msg, data);
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
