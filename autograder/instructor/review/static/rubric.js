// The rubric page after a save (a page load): the focus on the save button of the item or saved comment
// just saved (the address's #item-EXERCISE-ID or #bank-EXERCISE-KEY is its id), not lost to the page.
// (The button itself is the fragment's target: a target that takes no focus would take it away again.)
(() => {
  const button = location.hash.length > 1 && document.getElementById(decodeURIComponent(location.hash.slice(1)));
  if (button && button.tagName === 'BUTTON') button.focus();
})();
