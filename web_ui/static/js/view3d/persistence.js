// The 3D view's settings — displays, fixed frame, camera — kept in localStorage across reloads
// and saved to / loaded from a JSON file (as rviz's .rviz config). Whatever comes back from
// storage or a file is checked field by field: what is wrong is dropped and said, never applied.

const STORAGE_KEY = "skydeck.view3d";
export const FORMAT = "skydeck-view3d";
const VERSION = 1;
const MAX_DISPLAYS = 100;
const NAME = /^\/[A-Za-z0-9_/]*$/;
const TYPE = /^[A-Za-z0-9_]+\/msg\/[A-Za-z0-9_]+$/;
const COLOR = /^#[0-9a-fA-F]{6}$/;
const FRAME = /^[A-Za-z0-9_./-]{1,200}$/;

/** The settings as saved: plain data. */
export function settingsDocument({ fixedFrame, camera, grid, world, displays }) {
  return { format: FORMAT, version: VERSION, fixedFrame, camera, grid, world, displays };
}

/**
 * Check a parsed document: returns {settings, warnings}; throws an Error with a message for the
 * user when it is not a 3D view document at all. `knownType(type)` says which types have displays.
 */
export function checkDocument(doc, knownType) {
  if (!doc || typeof doc !== "object" || Array.isArray(doc)) throw new Error("not a JSON object");
  if (doc.format !== FORMAT) throw new Error(`not a Skydeck 3D view file (format should be "${FORMAT}")`);
  if (doc.version !== VERSION) throw new Error(`version ${JSON.stringify(doc.version)} is not one this page reads (${VERSION})`);
  const warnings = [];
  const settings = { fixedFrame: null, camera: null, grid: true, world: true, displays: [] };
  if (typeof doc.fixedFrame === "string" && FRAME.test(doc.fixedFrame)) settings.fixedFrame = doc.fixedFrame;
  else if (doc.fixedFrame != null) warnings.push("fixedFrame is not a frame name: the default is used");
  if (doc.camera != null) {
    const c = doc.camera;
    const vector = (v) => Array.isArray(v) && v.length === 3 && v.every(Number.isFinite);
    if (c && vector(c.position) && vector(c.target)) {
      // `world`: which world the view was on ("drone", "robot"); another one is framed afresh.
      const world = c.world === "drone" || c.world === "robot" ? c.world : null;
      settings.camera = { position: c.position, target: c.target, follow: c.follow === true, world };
    } else {
      warnings.push("camera is not {position: [x, y, z], target: [x, y, z]}: the default view is used");
    }
  }
  if (typeof doc.grid === "boolean") settings.grid = doc.grid;
  if (typeof doc.world === "boolean") settings.world = doc.world;
  const displays = Array.isArray(doc.displays) ? doc.displays : [];
  if (doc.displays != null && !Array.isArray(doc.displays)) warnings.push("displays is not a list");
  const seen = new Set();
  for (const [index, d] of displays.slice(0, MAX_DISPLAYS).entries()) {
    const where = `displays[${index}]`;
    if (!d || typeof d.topic !== "string" || !NAME.test(d.topic)) {
      warnings.push(`${where}: topic is not a ROS name`);
      continue;
    }
    if (typeof d.type !== "string" || !TYPE.test(d.type) || !knownType(d.type)) {
      warnings.push(`${where} (${d.topic}): no display for type ${JSON.stringify(d.type)}`);
      continue;
    }
    if (seen.has(d.topic)) {
      warnings.push(`${where}: ${d.topic} is there twice`);
      continue;
    }
    seen.add(d.topic);
    settings.displays.push({
      topic: d.topic,
      type: d.type,
      color: typeof d.color === "string" && COLOR.test(d.color) ? d.color : undefined,
      visible: d.visible !== false,
      options: d.options && typeof d.options === "object" && !Array.isArray(d.options) ? d.options : {},
    });
  }
  if (displays.length > MAX_DISPLAYS) warnings.push(`only the first ${MAX_DISPLAYS} displays are used`);
  return { settings, warnings };
}

/** Whether the last visit left settings (without reading them). */
export function hasStored() {
  try {
    return localStorage.getItem(STORAGE_KEY) !== null;
  } catch {
    return false;
  }
}

/** The settings of the last visit, or null (none, or unreadable: then ignored). */
export function loadStored(knownType) {
  try {
    const text = localStorage.getItem(STORAGE_KEY);
    return text ? checkDocument(JSON.parse(text), knownType).settings : null;
  } catch {
    return null;
  }
}

export function store(document) {
  try {
    localStorage.setItem(STORAGE_KEY, JSON.stringify(document));
  } catch {
    // storage full or refused (private mode): the view works, it just will not be remembered
  }
}

/** Offer `document` as a file download. */
export function downloadDocument(document, filename = "skydeck-view.json") {
  const blob = new Blob([`${JSON.stringify(document, null, 2)}\n`], { type: "application/json" });
  const url = URL.createObjectURL(blob);
  const link = Object.assign(window.document.createElement("a"), { href: url, download: filename });
  window.document.body.append(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}

/** Parse a chosen file: {settings, warnings}; throws an Error saying what is wrong with it. */
export async function readDocument(file, knownType) {
  if (file.size > 1_000_000) throw new Error("the file is over 1 MB: not a 3D view file");
  let doc;
  try {
    doc = JSON.parse(await file.text());
  } catch (error) {
    throw new Error(`not JSON (${error.message})`);
  }
  return checkDocument(doc, knownType);
}
