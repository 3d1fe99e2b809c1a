// The side panel's tabs: one visible at a time; others are hidden, not destroyed.

export class Tabs extends EventTarget {
  constructor(root) {
    super();
    this.buttons = [...root.querySelectorAll("[data-tab]")];
    this.panels = [...root.querySelectorAll("[data-tab-panel]")];
    for (const button of this.buttons) button.addEventListener("click", () => this.show(button.dataset.tab));
  }

  show(name) {
    for (const button of this.buttons) button.setAttribute("aria-selected", String(button.dataset.tab === name));
    for (const panel of this.panels) panel.hidden = panel.dataset.tabPanel !== name;
    this.current = name;
    this.dispatchEvent(new CustomEvent("change", { detail: name }));
  }
}
