// The WebSocket to the studio server. A Geometry message (JSON) is always
// followed by one binary frame with its float32 data; this pairs them.
import type { ClientMessage, Geometry, ServerMessage } from "./protocol";

export interface Handlers {
  geometry(msg: Geometry, data: Float32Array): void;
  message(msg: ServerMessage): void;
  closed(): void;
}

export class Connection {
  private ws: WebSocket;
  private pending: Geometry | null = null;
  private nextId = 1;

  constructor(url: string, private handlers: Handlers) {
    this.ws = new WebSocket(url);
    this.ws.binaryType = "arraybuffer";
    this.ws.onmessage = (ev) => this.receive(ev.data);
    this.ws.onclose = () => this.handlers.closed();
  }

  /** Send a message (its id is filled in) and return the id the reply will carry. */
  send(msg: ClientMessage): number {
    const id = this.nextId++;
    const text = JSON.stringify({ ...msg, id });
    if (this.ws.readyState === WebSocket.OPEN) this.ws.send(text);
    else this.ws.addEventListener("open", () => this.ws.send(text), { once: true });
    return id;
  }

  private receive(data: string | ArrayBuffer): void {
    if (typeof data === "string") {
      const msg = JSON.parse(data) as ServerMessage;
      if (msg.type === "geometry") this.pending = msg;
      else this.handlers.message(msg);
      return;
    }
    if (this.pending === null) return; // a binary frame always follows a geometry message
    const msg = this.pending;
    this.pending = null;
    this.handlers.geometry(msg, new Float32Array(data));
  }
}

/** The studio's WebSocket URL on the page's own host. */
export function socketUrl(loc: Location): string {
  return `${loc.protocol === "https:" ? "wss" : "ws"}://${loc.host}/ws`;
}
