// The evidence strip: per segmentation view, the propagated clicks, the SAM mask, the
// rendered 3D selection and whether inspection accepted or dropped the view.
const LABELS = { accepted: 'accepted', dropped: 'dropped', 'no-clicks': 'no click', 'empty-mask': 'empty mask', skipped: 'skipped' };

export class Strip {
  constructor(root, onPick) { this.root = root; this.onPick = onPick; this.version = -1; this.cards = []; }

  update(seg, currentCamera) {
    const views = seg.views || [];
    if (!views.length) {
      if (this.version !== -2) {
        const why = seg.state === 'off' || seg.state === 'error' ? seg.message : 'The views appear here once segmentation is ready.';
        this.root.innerHTML = '';
        const d = document.createElement('div'); d.className = 'empty'; d.textContent = why; this.root.append(d);
        this.version = -2; this.cards = [];
      }
      return;
    }
    if (seg.thumb_version !== this.version || this.cards.length !== views.length) {
      this.root.innerHTML = '';
      this.cards = views.map((v) => {
        const card = document.createElement('div');
        card.className = 'thumb';
        card.dataset.status = v.status;
        card.dataset.camera = v.camera;
        const img = document.createElement('img');
        img.src = `/api/thumb?index=${v.index}&v=${seg.thumb_version}`;
        img.alt = v.name;
        const meta = document.createElement('div'); meta.className = 'meta';
        const name = document.createElement('span'); name.className = 'name';
        const clicks = v.positive || v.negative ? ` · +${v.positive}${v.negative ? ' −' + v.negative : ''}` : '';
        name.textContent = (v.camera >= 0 ? v.name : 'free camera') + clicks;
        const badge = document.createElement('span'); badge.className = `badge ${v.status}`;
        badge.dataset.label = LABELS[v.status] || v.status;
        meta.append(name, badge);
        card.append(img, meta);
        let tip = `${v.name}: ${v.status_text}`;
        if (v.mask_pixels) {
          tip += `\nSAM mask ${v.mask_pixels} px, score ${v.sam_score.toFixed(2)}, `;
          // The clicked view votes first: nothing to inspect it against, so no overlap figure.
          tip += v.inspected ? `overlap with selection ${(100 * v.overlap).toFixed(0)}%` : 'not inspected (clicked view or inspection off)';
        }
        if (v.not_sent) tip += `\n${v.not_sent} click(s) not sent: ${v.not_sent_reason}`;
        card.title = tip;
        if (v.camera >= 0) card.addEventListener('click', () => this.onPick(v.camera));
        this.root.append(card);
        return card;
      });
      this.version = seg.thumb_version;
    }
    for (const c of this.cards) c.classList.toggle('current', Number(c.dataset.camera) === currentCamera);
    // After an edit the evidence is of the scene before it: say so instead of showing it
    // as the current verdict.
    this.root.classList.toggle('stale', !!seg.stale);
    this.root.title = seg.stale ? 'evidence of the scene before the last edit; the next click segments the edited scene' : '';
    for (const b of this.root.querySelectorAll('.badge')) b.textContent = seg.stale ? 'before edit' : b.dataset.label;
  }
}
