// Files: export in every format the server writes (download, or save on the server) and
// a second scene to combine, picked from the data folder (`--data-dir`) or uploaded.
const $ = (id) => document.getElementById(id);

export const FORMATS = [
  { ext: 'ply', label: 'PLY (INRIA, full SH)' },
  { ext: 'compressed.ply', label: 'Compressed PLY (SuperSplat)' },
  { ext: 'splat', label: '.splat (no SH)' },
  { ext: 'spz', label: 'SPZ (Niantic)' },
  { ext: 'sog', label: 'SOG (PlayCanvas)' },
];

const stripExt = (name) => name.replace(/\.(compressed\.ply|ply|splat|spz|sog)$/i, '');

function size(bytes) {
  if (bytes >= 1 << 20) return `${(bytes / (1 << 20)).toFixed(1)} MiB`;
  if (bytes >= 1 << 10) return `${Math.round(bytes / 1024)} KiB`;
  return `${bytes} B`;
}

export class Files {
  // transform(): the panel's move/rotate/scale for the inserted scene.
  constructor({ api, run, scene, transform }) {
    Object.assign(this, { api, run, scene, transform });
    const fmt = $('export-format');
    for (const f of FORMATS) fmt.add(new Option(f.label, f.ext));
    fmt.addEventListener('change', () => {
      const p = $('export-path');
      p.value = `${stripExt(p.value.trim()) || 'edited'}.${fmt.value}`;
    });
    $('btn-download').addEventListener('click', () => this.download(fmt.value));
    $('btn-save').addEventListener('click', () => this.run(async () => {
      const r = await this.api.post('/api/export', { path: $('export-path').value.trim() });
      return `saved ${r.gaussians.toLocaleString()} Gaussians to ${r.path}` + (r.notes.length ? ` (${r.notes.join('; ')})` : '');
    }));
    $('btn-files-refresh').addEventListener('click', () => this.refresh());
    $('upload-file').addEventListener('change', () => this.upload());
    $('btn-combine').addEventListener('click', () => this.combine());
    this.refresh();
  }

  download(ext) {
    const a = document.createElement('a');
    a.href = `/api/export?format=${encodeURIComponent(ext)}`;
    a.download = `${this.scene.name || 'scene'}-edited.${ext}`;
    document.body.append(a); a.click(); a.remove();
  }

  async refresh(select) {
    try {
      const f = await this.api.get('/api/files');
      this.maxUpload = f.max_upload_bytes;
      const list = $('combine-source');
      list.replaceChildren();
      const data = document.createElement('optgroup');
      data.label = f.data_dir ? `data folder ${f.data_dir}` : 'no data folder (--data-dir)';
      for (const e of f.files)
        data.append(new Option(`${e.name}${e.kind === 'folder' ? '/' : ''}  ${e.kind === 'file' ? size(e.bytes) : 'scene folder'}`,
          JSON.stringify({ path: e.name })));
      const up = document.createElement('optgroup');
      up.label = 'uploaded';
      for (const e of f.uploads)
        up.append(new Option(`${e.name}  ${e.gaussians.toLocaleString()} Gaussians`, JSON.stringify({ upload: e.name })));
      list.append(data, up);
      if (select) list.value = JSON.stringify(select);
      $('btn-combine').disabled = list.options.length === 0;
      $('upload-hint').textContent = `upload any splat file up to ${size(f.max_upload_bytes)}`;
    } catch (e) {
      $('upload-hint').textContent = `cannot list the files: ${e.message}`;
    }
  }

  upload() {
    const input = $('upload-file'), file = input.files[0];
    if (!file) return null;
    return this.run(async () => {
      if (this.maxUpload && file.size > this.maxUpload)
        throw new Error(`${file.name} is ${size(file.size)}: more than the server takes (${size(this.maxUpload)})`);
      $('upload-hint').textContent = `uploading ${file.name} (${size(file.size)})…`;
      const res = await fetch(`/api/upload?name=${encodeURIComponent(file.name)}`, {
        method: 'POST', headers: { 'Content-Type': 'application/octet-stream' }, body: file });
      const j = await res.json().catch(() => ({}));
      input.value = '';
      if (!res.ok) { await this.refresh(); throw new Error(j.error || `upload failed (${res.status})`); }
      await this.refresh({ upload: j.name });
      return `uploaded ${j.name}: ${j.gaussians.toLocaleString()} Gaussians`;
    });
  }

  combine() {
    const v = $('combine-source').value;
    if (!v) return null;
    return this.run(async () => {
      const r = await this.api.post('/api/edit/combine', { ...JSON.parse(v), ...this.transform() });
      return r.label + (r.notes && r.notes.length ? ` (${r.notes.join('; ')})` : '');
    });
  }
}
