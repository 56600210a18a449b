// The string unions of the looks, re-exported from the generated protocol's message fields.
import type { GetMesh } from "./protocol";

export type Style = NonNullable<GetMesh["style"]>;
export type FacesMode = NonNullable<GetMesh["faces"]>;
