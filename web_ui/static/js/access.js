// What the page's token may do (GET /api/access), for a class (docs/class.md): a student's
// dashboard lists and opens only what their token may read, and drives only what it may publish
// on; the instructor's shows the Class tab. With no class every name is allowed, as before.

import { apiFetch } from "./api.js";
import { requestToken } from "./auth.js";

/** Whether `name` is `pattern` or under it (`/bob/**` holds `/bob` and `/bob/scan`): the
 * policy's own matching (services/access/policy.py name_matches). */
export function nameMatches(pattern, name) {
  if (pattern.endsWith("/**")) {
    const base = pattern.slice(0, -3);
    return !base || name === base || name.startsWith(`${base}/`);
  }
  return name === pattern;
}

export class Access extends EventTarget {
  constructor() {
    super();
    this.described = null; // GET /api/access's answer; null until the core answered
  }

  /** Ask the core who the token is (again: after the token changed). */
  async refresh() {
    try {
      const response = await apiFetch("/api/access");
      if (!response.ok) return;
      this.described = await response.json();
    } catch {
      return; // the core is not reachable: the status banner says so
    }
    if (this.inClass && this.role === "anonymous") {
      // In a class nothing opens without a token: ask for it once, as a refused socket would.
      requestToken("This core runs a class: enter your class token (the instructor hands it out).", { userAction: false });
    }
    this.dispatchEvent(new Event("change"));
  }

  get inClass() {
    return Boolean(this.described && this.described.class);
  }

  get role() {
    return this.described ? this.described.role : null;
  }

  /** The instructor (or the class's own processes' token): everything, and the class page. */
  get isInstructor() {
    return this.inClass && (this.role === "instructor" || this.role === "operator");
  }

  get namespace() {
    return this.described ? this.described.namespace : "/";
  }

  may(verb, name) {
    const may = this.described && this.described.may;
    if (!this.inClass || !may) return true;
    return (may[verb] || []).some((pattern) => nameMatches(pattern, name));
  }

  mayRead(name) {
    return this.may("read", name);
  }

  /** The graph as this token sees it: topics it may read, services it may call, and the nodes
   * of its own namespace or publishing something it may read. */
  filterGraph(graph) {
    if (!graph || !this.inClass || this.isInstructor) return graph;
    const own = (name) => nameMatches(`${this.namespace}/**`, name);
    return {
      ...graph,
      topics: graph.topics.filter((t) => this.mayRead(t.name)),
      services: graph.services.filter((s) => this.may("call", s.name)),
      nodes: graph.nodes.filter((n) => own(n.name) || (n.publications || []).some((t) => this.mayRead(t))),
    };
  }
}
