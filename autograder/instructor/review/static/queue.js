// The queue by keyboard: j/n and k/p move, Enter opens, u opens the first not reviewed; a, t, r pick the filter.
(() => {
  const rows = [...document.querySelectorAll('#queue tr[data-position]')];
  const filters = Object.fromEntries([...document.querySelectorAll('#filters a[data-key]')].map(a => [a.dataset.key, a]));
  let at = 0;
  const show = () => rows.forEach((r, i) => r.style.outline = i === at ? '2px solid #0969da' : '');
  document.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    if (e.key === 'j' || e.key === 'n') at = Math.min(at + 1, rows.length - 1);
    else if (e.key === 'k' || e.key === 'p') at = Math.max(at - 1, 0);
    else if (e.key === 'Enter' && rows.length) location.href = rows[at].querySelector('a').href;
    else if (e.key === 'u') { const r = rows.find(r => r.dataset.done === '0'); if (r) location.href = r.querySelector('a').href; }
    else if (filters[e.key]) location.href = filters[e.key].href;
    else return;
    e.preventDefault(); show();
  });
  show();
})();
