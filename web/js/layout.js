// Collapsible panel cards, so the panel fits a 1366x768 screen: a card's title toggles it
// (remembered per card); on short windows the secondary cards start collapsed. Children
// marked `.keep` stay visible when their card is collapsed.
const KEY = 'isegman.collapsed';
const SECONDARY = ['card-seg', 'card-log'];

export function initLayout() {
  let saved = null;
  try { saved = JSON.parse(localStorage.getItem(KEY) || 'null'); } catch (_) { saved = null; }
  const collapsed = new Set(saved || (window.innerHeight < 900 ? SECONDARY : []));
  const store = () => { try { localStorage.setItem(KEY, JSON.stringify([...collapsed])); } catch (_) { /* private mode */ } };
  for (const card of document.querySelectorAll('.panel .card')) {
    const title = card.querySelector('h2');
    if (!title || !card.id) continue;
    title.classList.add('collapsible');
    title.title = 'Show / hide this panel';
    card.classList.toggle('collapsed', collapsed.has(card.id));
    title.addEventListener('click', (e) => {
      if (e.target.closest('button, input, select')) return;
      card.classList.toggle('collapsed');
      if (card.classList.contains('collapsed')) collapsed.add(card.id); else collapsed.delete(card.id);
      store();
    });
  }
}
