// The right-hand panel: segmentation settings, selection helpers, the toolbox, history
// and export. Every action goes through `run`, which shows errors and refreshes state.
const $ = (id) => document.getElementById(id);
const vec = (name) => [...document.querySelectorAll(`[data-vec="${name}"] input`)];
const readVec = (name) => vec(name).map((i) => Number(i.value));
const writeVec = (name, v) => vec(name).forEach((i, k) => { i.value = Number(v[k].toPrecision(5)); });

export function scaleFactor() { return Math.exp(Number($('scale').value)); }

export class Panels {
  constructor({ api, run, runJob, scene, onClickWalked }) {
    Object.assign(this, { api, run, runJob, scene, onClickWalked: onClickWalked || (() => {}) });
    this.selMode = 'replace';
    this.bind();
  }

  transform() {
    return { translate: readVec('tr'), rotate: readVec('rot'), scale: Number($('tr-scale').value) };
  }

  bind() {
    const { api, run, runJob } = this;
    $('tau').addEventListener('input', () => { $('tau-out').textContent = Number($('tau').value).toFixed(2); });
    $('btn-settings').addEventListener('click', () => runJob('applying settings', () => api.post('/api/settings', {
      tau: Number($('tau').value), views: $('views').value, mode: $('mode').value, inspection: $('inspection').checked })));
    $('btn-undo').addEventListener('click', () => this.undo());
    $('btn-redo').addEventListener('click', () => this.redo());

    for (const b of document.querySelectorAll('#sel-mode button')) {
      b.addEventListener('click', () => {
        this.selMode = b.dataset.mode;
        for (const o of document.querySelectorAll('#sel-mode button')) o.classList.toggle('on', o === b);
      });
    }
    $('btn-fit').addEventListener('click', () => run(async () => {
      const b = await api.get('/api/selection/bounds');
      writeVec('box-lo', b.lo); writeVec('box-hi', b.hi); writeVec('sph-c', b.center);
      $('sph-r').value = Number(b.radius.toPrecision(5));
      return null;
    }));
    $('btn-box').addEventListener('click', () => run(() => api.post('/api/select/box', { lo: readVec('box-lo'), hi: readVec('box-hi'), mode: this.selMode })));
    $('btn-sphere').addEventListener('click', () => run(() => api.post('/api/select/sphere', {
      center: readVec('sph-c'), radius: Number($('sph-r').value), mode: this.selMode })));
    $('btn-invert').addEventListener('click', () => this.select('invert'));
    $('btn-clear').addEventListener('click', () => this.select('clear'));
    $('btn-all').addEventListener('click', () => this.select('all'));

    $('btn-remove').addEventListener('click', () => this.edit('remove'));
    $('btn-colorize').addEventListener('click', () => this.edit('colorize', { color: $('color').value, mode: $('color-mode').value }));
    $('scale').addEventListener('input', () => { $('scale-out').textContent = `×${scaleFactor().toFixed(2)}`; });
    $('btn-scale').addEventListener('click', () => this.edit('scale', { factor: Number(scaleFactor().toFixed(4)) }));
    $('btn-copy').addEventListener('click', () => this.edit('copy', this.transform()));
    $('btn-move').addEventListener('click', () => this.edit('transform', this.transform()));
    $('btn-extract').addEventListener('click', () => this.edit('extract'));

    $('scale-out').textContent = `×${scaleFactor().toFixed(2)}`;
  }

  select(tool) { return this.run(() => this.api.post(`/api/select/${tool}`, { mode: this.selMode })); }
  edit(op, body = {}) {
    return this.run(async () => {
      const r = await this.api.post(`/api/edit/${op}`, body);
      return r.label + (r.notes && r.notes.length ? ` (${r.notes.join('; ')})` : '');
    });
  }
  // One history of clicks, selections and edits (POST /api/undo, /api/redo).
  undo() { return this.walk('undo'); }
  redo() { return this.walk('redo'); }
  walk(dir) {
    return this.run(async () => {
      const r = await this.api.post(`/api/${dir}`);
      if (r.kind === 'click') this.onClickWalked(dir, r.job);
      return `${dir}: ${r.label}`;
    });
  }

  // The history list: "start", then every step; the current one highlighted, the undone
  // ones dimmed.
  showHistory(h) {
    if (!h) return;
    $('btn-undo').disabled = !h.can_undo;
    $('btn-redo').disabled = !h.can_redo;
    document.body.dataset.historyCursor = String(h.cursor);
    document.body.dataset.historySteps = String(h.entries.length);
    $('history-info').textContent = `step ${h.cursor} of ${h.entries.length}`;
    const key = JSON.stringify(h);
    if (key === this.historyKey) return;
    this.historyKey = key;
    const list = $('history-list');
    const items = [{ kind: 'start', label: 'start' }, ...h.entries].map((e, i) => {
      const li = document.createElement('li');
      li.className = `${e.kind}${i === h.cursor ? ' current' : ''}${i > h.cursor ? ' undone' : ''}`;
      if (e.kind === 'start') li.textContent = 'start (as loaded)';
      else {
        const k = document.createElement('span');
        k.className = 'k'; k.textContent = e.kind;
        li.append(k, document.createTextNode(e.label));
      }
      li.title = e.label;
      return li;
    });
    list.replaceChildren(...items);
    const cur = list.children[h.cursor];
    // Keep the current step in view by scrolling the list only (scrollIntoView would
    // scroll the whole panel too).
    if (cur) {
      const top = cur.offsetTop, bottom = top + cur.offsetHeight;
      if (top < list.scrollTop) list.scrollTop = top;
      else if (bottom > list.scrollTop + list.clientHeight) list.scrollTop = bottom - list.clientHeight;
    }
  }

  // Enables the controls that make sense in the current state.
  update(status) {
    const seg = status.segmentation, ed = status.edit;
    const segReady = seg.state === 'ready';
    const has = ed.selected > 0;
    $('btn-settings').disabled = !(segReady || seg.state === 'preparing');
    for (const id of ['btn-remove', 'btn-extract', 'btn-colorize', 'btn-scale', 'btn-copy', 'btn-move']) $(id).disabled = !has;
    $('btn-invert').disabled = false;
    this.showHistory(status.history);
    if (!this.settingsShown && seg.settings) {
      this.settingsShown = true;
      $('tau').value = seg.settings.tau; $('tau-out').textContent = Number(seg.settings.tau).toFixed(2);
      const v = $('views');
      if (![...v.options].some((o) => o.value === seg.settings.views)) v.add(new Option(seg.settings.views, seg.settings.views));
      v.value = seg.settings.views;
      $('mode').value = seg.settings.mode;
      $('inspection').checked = seg.settings.inspection;
    }
  }
}
