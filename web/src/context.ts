// What every front-end module gets: the state, the server connection and the views.
import type { Connection, Reply } from "./connection";
import type { ClientMessage } from "./protocol";
import type { Views } from "./scene";
import type { Store } from "./store";

export interface Ctx {
  store: Store;
  conn: Connection;
  views: Views;
  /** Send a message; returns its id. */
  send(msg: ClientMessage): number;
  /** Send and await the reply (rejects on an error reply, which is also shown in the status bar).
   * `input`: the timeStamp of the user input it answers, for the edit timings. */
  request(msg: ClientMessage, input?: number): Promise<Reply>;
}
