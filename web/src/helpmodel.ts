// The help overlay's pure part: registered shortcuts grouped by what they do, one row per action.
import { describeKeys, type Shortcut } from "./shortcuts";

export interface HelpRow {
  description: string;
  /** Every key combination of the action, e.g. ["Ctrl+Shift+Z", "Ctrl+Y"]. */
  keys: string[];
}

export interface HelpGroup {
  title: string;
  rows: HelpRow[];
}

// A shortcut goes to the first group whose pattern matches its description; the rest are tools.
const GROUPS: [string, RegExp | null][] = [
  ["Files", /\b(save|open|export|new|gallery)\b/i],
  ["Edit", /\b(undo|redo|delete|remove|copy|paste|duplicate|cancel|select all)\b/i],
  ["Tools", null],
  ["View", /\b(mode|fit|zoom|views?|help|show|hide)\b/i],
];

/** Shortcuts grouped (Files, Edit, Tools, View, in registration order); no empty groups. */
export function helpGroups(list: readonly Shortcut[]): HelpGroup[] {
  const groups = GROUPS.map(([title]) => ({ title, rows: [] as HelpRow[] }));
  const rest = GROUPS.findIndex(([, re]) => re === null);
  for (const s of list) {
    const i = GROUPS.findIndex(([, re]) => re !== null && re.test(s.description));
    const g = groups[i >= 0 ? i : rest];
    const keys = describeKeys(s);
    const row = g.rows.find((r) => r.description === s.description);
    if (!row) g.rows.push({ description: s.description, keys: [keys] });
    else if (!row.keys.includes(keys)) row.keys.push(keys);
  }
  return groups.filter((g) => g.rows.length);
}
