// The optional access token: asked for once when the core answers 401 (HTTP) or closes a
// socket for a missing token (1008), kept in sessionStorage for this tab only.

const STORAGE_KEY = "skydeck.token";
let pending = null; // one dialog at a time, shared by every caller that hit a 401
let declined = false; // after a Cancel, background requests stop asking; user actions still may

export function getToken() {
  return sessionStorage.getItem(STORAGE_KEY) || "";
}

function setToken(token) {
  if (token) sessionStorage.setItem(STORAGE_KEY, token);
  else sessionStorage.removeItem(STORAGE_KEY);
  window.dispatchEvent(new Event("skydeck-token")); // who the page is may change (access.js)
}

/**
 * Ask the user for the token; resolves true when a (new) token was given. Background callers
 * (polls) pass `{ userAction: false }` so a cancelled dialog does not come back every second.
 */
export function requestToken(reason = "The core needs an access token for this.", { userAction = true } = {}) {
  if (pending) return pending;
  if (declined && !userAction) return Promise.resolve(false);
  const dialog = document.getElementById("token-dialog");
  const input = document.getElementById("token-input");
  document.getElementById("token-reason").textContent = reason;
  input.value = getToken();
  pending = new Promise((resolve) => {
    dialog.addEventListener(
      "close",
      () => {
        pending = null;
        if (dialog.returnValue === "save" && input.value.trim()) {
          setToken(input.value.trim());
          declined = false;
          resolve(true);
        } else {
          declined = true;
          resolve(false);
        }
      },
      { once: true },
    );
  });
  dialog.returnValue = "";
  dialog.showModal();
  input.focus();
  return pending;
}

export function initTokenButton(button) {
  button.addEventListener("click", () => requestToken("Set or change the access token for this tab."));
}
