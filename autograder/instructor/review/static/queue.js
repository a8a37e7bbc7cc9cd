// The queue by keyboard: j/n and k/p move, Enter opens, u opens the first not reviewed; a, t, r pick the filter.
// The row chosen and the focus are one: j/k move the focus to the row's link, Tab to a link chooses its row,
// and Enter on a focused link or button is the browser's own (it opens what has the focus, never another row).
(() => {
  const rows = [...document.querySelectorAll('#queue tr[data-position]')];
  const filters = Object.fromEntries([...document.querySelectorAll('#filters a[data-key]')].map(a => [a.dataset.key, a]));
  let at = 0;
  const show = () => rows.forEach((r, i) => r.classList.toggle('chosen', i === at));
  const choose = (i) => { at = i; show(); rows[at].querySelector('a').focus(); };
  document.addEventListener('focusin', (e) => {
    const row = e.target.closest && e.target.closest('#queue tr[data-position]');
    if (row) { at = rows.indexOf(row); show(); }
  });
  document.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const onControl = e.target.closest && e.target.closest('a[href], button, input, textarea, select, summary');
    if (e.key === 'Enter' && onControl) return;   // the focused link opens itself
    if (!rows.length && !filters[e.key]) return;
    if (e.key === 'j' || e.key === 'n') choose(Math.min(at + 1, rows.length - 1));
    else if (e.key === 'k' || e.key === 'p') choose(Math.max(at - 1, 0));
    else if (e.key === 'Enter') location.href = rows[at].querySelector('a').href;
    else if (e.key === 'u') { const r = rows.find(r => r.dataset.done === '0'); if (r) location.href = r.querySelector('a').href; }
    else if (filters[e.key]) location.href = filters[e.key].href;
    else return;
    e.preventDefault();
  });
  show();
})();
