// The review screen: every change saved at once, by mouse or keyboard. No inline script: the page's
// addresses and the form secret come from the #review element's data attributes.
(() => {
  const root = document.getElementById('review');
  // This student's exercise, wherever the queue has it when the request arrives (a batch may add students).
  const base = root.dataset.base, csrf = root.dataset.csrf;
  const status = document.getElementById('status');
  const comment = document.getElementById('comment');
  const boxes = [...document.querySelectorAll('#rubric input[type=checkbox]')];
  const saved = [...document.querySelectorAll('#bank button.saved')];
  const figures = [...document.querySelectorAll('#figures img')];
  let pending = Promise.resolve(), savedComment = comment.value, timer = null, inserting = false;

  const post = (path, fields) => {
    const body = new URLSearchParams({csrf, ...fields});
    status.textContent = 'saving…';
    pending = pending.then(() => fetch(base + path, {method: 'POST', body, headers: {'Accept': 'application/json'}}))
      .then(r => { if (!r.ok) throw new Error('the server answered ' + r.status); return r.json(); })
      .then(show)
      .catch(e => { status.textContent = 'NOT SAVED: ' + e.message; status.className = 'bad'; });
    return pending;
  };
  const show = (s) => {
    boxes.forEach(b => b.checked = s.applied.includes(b.dataset.item));
    document.getElementById('points').textContent = +s.points.toFixed(4);
    const done = document.getElementById('done');
    done.textContent = s.done ? 'reviewed' : 'not reviewed yet';
    done.className = s.done ? 'done' : 'muted';
    document.getElementById('changed').textContent = s.changed_by ? `last change: ${s.changed_by}, ${s.changed_at}` : '';
    status.textContent = 'saved'; status.className = 'done';
  };
  const saveComment = () => {
    clearTimeout(timer);
    if (comment.value === savedComment) return pending;
    savedComment = comment.value;
    return post('/note', {comment: comment.value});
  };
  const saveDone = () => { savedComment = comment.value; return post('/note', {comment: comment.value, done: '1'}); };
  const go = (where) => saveComment().then(() => pending).then(() => {
    location.href = where === 'queue' ? root.dataset.queue : base + '/step/' + where;
  });
  // A saved comment is copied into this student's comment: editing the saved one later leaves this copy as it is.
  const insert = (button) => {
    const text = button.dataset.text;
    comment.value = comment.value.trim() ? comment.value.replace(/\s*$/, '') + '\n' + text : text;
    return saveComment();
  };
  const toggle = (box) => post('/mark', {item: box.dataset.item, applied: box.checked ? '1' : '0'});

  boxes.forEach(b => b.addEventListener('change', () => toggle(b)));
  saved.forEach(b => b.addEventListener('click', () => insert(b)));
  figures.forEach(f => f.addEventListener('click', () => f.classList.toggle('fit')));
  document.getElementById('save').addEventListener('click', saveDone);
  document.getElementById('save-to-bank').addEventListener('submit', () => {
    document.getElementById('bank-text').value = comment.value;
    savedComment = comment.value;   // the form reloads the page: the comment is posted with it below
    navigator.sendBeacon && navigator.sendBeacon(base + '/note', new URLSearchParams({csrf, comment: comment.value}));
  });
  // Back from saving a comment for reuse (a page load): the focus on its new button, not lost to the page.
  const justSaved = location.hash.startsWith('#saved-') && saved.find(b => '#' + b.id === location.hash);
  if (justSaved) justSaved.focus();
  comment.addEventListener('input', () => { clearTimeout(timer); timer = setTimeout(saveComment, 400); });
  comment.addEventListener('blur', saveComment);
  window.addEventListener('beforeunload', saveComment);

  document.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const typing = document.activeElement && ['TEXTAREA', 'INPUT'].includes(document.activeElement.tagName)
      && document.activeElement.type !== 'checkbox';
    if (typing) {
      if (e.key === 'Escape') { document.activeElement.blur(); e.preventDefault(); }
      return;
    }
    if (inserting) {   // "v" then a digit: that saved comment
      inserting = false;
      if (/^[1-9]$/.test(e.key) && saved[+e.key - 1]) { insert(saved[+e.key - 1]); e.preventDefault(); }
      return;
    }
    if (/^[1-9]$/.test(e.key)) {
      const box = boxes[+e.key - 1];
      if (box) { box.checked = !box.checked; toggle(box); }
    } else if (e.key === 'c') { comment.focus(); }
    else if (e.key === 'v') { inserting = saved.length > 0; status.textContent = inserting ? 'saved comment: 1…' + Math.min(saved.length, 9) : ''; }
    else if (e.key === 's') { saveDone(); }
    else if (e.key === 'z') { const fit = !figures.every(f => f.classList.contains('fit')); figures.forEach(f => f.classList.toggle('fit', fit)); }
    else if (e.key === 'j' || e.key === 'n') { go('next'); }
    else if (e.key === 'k' || e.key === 'p') { go('previous'); }
    else if (e.key === 'e') { location.href = root.dataset.rubric; }
    else if (e.key === 'q') { go('queue'); }
    else return;
    e.preventDefault();
  });
})();
