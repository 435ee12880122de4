// How the selection is shown: highlight on/off and its opacity, hide / isolate the
// selection and show all (a display state on the server: the page's WebGL view and the
// server renders leave hidden Gaussians out; the scene, the history and exports do not).
const $ = (id) => document.getElementById(id);

export function bindDisplay({ api, run, viewer }) {
  const highlight = () => viewer.setHighlight($('hl-on').checked, Number($('hl-opacity').value));
  $('hl-on').addEventListener('change', highlight);
  $('hl-opacity').addEventListener('input', highlight);
  // The slider moves the WebGL tint at once; server renders follow when it is let go.
  $('hl-opacity').addEventListener('change', highlight);
  const display = (op) => run(async () => {
    const r = await api.post(`/api/display/${op}`);
    document.body.dataset.hidden = String(r.hidden);
    viewer.refresh();
    return r.label;
  });
  $('btn-hide').addEventListener('click', () => display('hide'));
  $('btn-isolate').addEventListener('click', () => display('isolate'));
  $('btn-show-all').addEventListener('click', () => display('show'));
  highlight();
  return {
    // Hide / isolate need a selection; show all needs something hidden (when known).
    update(status) {
      const has = status.edit.selected > 0;
      $('btn-hide').disabled = !has;
      $('btn-isolate').disabled = !has;
      const hidden = document.body.dataset.hidden;
      $('btn-show-all').disabled = hidden === '0';
    },
  };
}
