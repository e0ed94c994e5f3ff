// The browser player: shows the storyboard raystep wrote into the page (the data below the body), step by
// step. Everything it shows was computed by raystep's replay model in C++; this script only picks the step.
'use strict';

(async function player() {
  const $ = (id) => document.getElementById(id);
  const packed = $('raystep-data').textContent.replace(/\s+/g, '');
  const bytes = Uint8Array.from(atob(packed), (c) => c.charCodeAt(0));
  const inflated = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('gzip'));
  const data = JSON.parse(await new Response(inflated).text());

  const rays = [];
  for (const w of data.walks) for (const r of w.rays) rays.push({ walk: w, ray: r });
  $('source').textContent = data.source;
  for (const [i, e] of rays.entries()) {
    const option = document.createElement('option');
    option.value = String(i);
    option.textContent = e.ray.header;
    $('ray').appendChild(option);
  }
  $('ray-choice').hidden = rays.length < 2;

  // The 3D view of a 3D walk (view3d.js, with three.js), made when a ray with a 3D walk is first shown.
  let view3d = null;
  let view3dScene = null;
  let current = null;  // the ray shown
  const quiz = { open: false, ray: null, step: -1 };  // a lesson's question not answered yet, and where
  let step = 0;
  let timer = null;

  // The state text as `raystep replay` writes it: the lines before "  why: " are the state, the rest the Why
  // text (its continuation lines indented under it).
  function split(text) {
    const at = text.indexOf('\n  why: ');
    if (at < 0) return { state: text, why: '' };
    const why = text.slice(at + 8).replace(/\n {7}/g, '\n').replace(/\n$/, '');
    return { state: text.slice(0, at + 1), why };
  }

  function showRay(index) {
    current = rays[index];
    const r = current.ray;
    const list = $('events');
    list.textContent = '';
    for (const [k, line] of r.lines.entries()) {
      const li = document.createElement('li');
      li.textContent = line.replace(/^\d+\s+/, '');
      li.addEventListener('click', () => go(k));
      list.appendChild(li);
    }
    $('slider').max = String(r.lines.length - 1);
    const picture = $('picture');
    picture.hidden = !r.picture;
    if (r.picture) {
      $('pic-under').innerHTML = r.picture.under;
      $('pic-over').innerHTML = r.picture.over;
      const svg = $('pic-under').querySelector('svg');
      picture.style.width = svg.getAttribute('width') + 'px';
      picture.style.height = svg.getAttribute('height') + 'px';
    }
    $('view3d').hidden = !r.walk3d;
    if (r.walk3d && window.raystepView3d) {
      const scene = data.scenes && current.walk.scene !== undefined ? data.scenes[current.walk.scene] : null;
      if (!view3d || view3dScene !== scene) {  // a view for each scene in turn
        $('view3d').textContent = '';
        view3d = window.raystepView3d.createView($('view3d'), scene);
        view3dScene = scene;
      }
      view3d.setRay(r.walk3d);
    }
    go(Math.min(step, r.lines.length - 1), true);
  }

  function go(k, force) {
    const r = current.ray;
    k = Math.max(0, Math.min(r.lines.length - 1, k));
    if (k === step && !force) return;
    const items = $('events').children;
    for (const li of $('events').querySelectorAll('li.current')) li.classList.remove('current');
    step = k;
    items[step].classList.add('current');
    items[step].scrollIntoView({ block: 'nearest' });
    // An open question at its own step: what would give the answer away waits for the prediction.
    const hide = quiz.open && quiz.ray === current && step === quiz.step;
    document.body.classList.toggle('concealed', hide);
    // (As the debugger conceals: the events after this one, the next axis a cell's line names, the Why text.)
    const untold = (line) => (hide ? line.replace(/\s+next \w+$/, '') : line);
    for (const [i, li] of Array.from(items).entries()) {
      li.classList.toggle('later', hide && i > step);
      li.textContent = untold(r.lines[i].replace(/^\d+\s+/, ''));
    }
    const parts = split(r.states[step]);
    $('state').textContent = hide ? parts.state.replace(/^([^\n]*?)\s+next \w+\n/, '$1\n') : parts.state;
    $('why').textContent = hide ? 'Shown with the answer.' : parts.why;
    $('slider').value = String(step);
    $('position').textContent = step + ' / ' + (r.lines.length - 1);
    if (r.picture) {
      $('pic-walk').innerHTML = r.picture.walk[step];
      $('pic-top').innerHTML = r.picture.top[step];
      $('caption').textContent = r.picture.caption[step].map((l) => (hide ? l.replace(/\s+next step: .*$/, '') : l))
          .map(untold).join('\n');
    } else {
      $('caption').textContent = untold(r.lines[step]);
    }
    if (view3d && r.walk3d) view3d.setStep(step);
    document.body.dataset.step = String(step);
  }

  function play() {
    if (timer) {
      clearInterval(timer);
      timer = null;
      $('play').textContent = 'Play';
      return;
    }
    if (step >= current.ray.lines.length - 1) go(0);
    $('play').textContent = 'Pause';
    timer = setInterval(() => {
      if (step >= current.ray.lines.length - 1) play();
      else go(step + 1);
    }, 400);
  }

  $('first').addEventListener('click', () => go(0));
  $('back').addEventListener('click', () => go(step - 1));
  $('forward').addEventListener('click', () => go(step + 1));
  $('last').addEventListener('click', () => go(current.ray.lines.length - 1));
  $('play').addEventListener('click', play);
  $('slider').addEventListener('input', (e) => go(Number(e.target.value)));
  $('ray').addEventListener('change', (e) => showRay(Number(e.target.value)));
  document.addEventListener('keydown', (e) => {
    if (e.target.tagName === 'SELECT' || e.target.tagName === 'INPUT' || e.altKey || e.ctrlKey || e.metaKey) return;
    if (!current) return;
    const keys = { ArrowRight: () => go(step + 1), ArrowLeft: () => go(step - 1), Home: () => go(0),
                   End: () => go(current.ray.lines.length - 1), ' ': play };
    if (keys[e.key]) {
      e.preventDefault();
      keys[e.key]();
    }
  });

  // A lesson: its steps, each with its walk at its event (or none) and its question.
  const lesson = data.lesson;
  let lessonStep = 0;
  const rayIndex = (walk, ray) => rays.findIndex((e) => e.walk.walk === walk && e.ray.ray === ray);

  function showLessonStep(i) {
    lessonStep = Math.max(0, Math.min(lesson.steps.length - 1, i));
    const s = lesson.steps[lessonStep];
    $('lesson-position').textContent = 'Step ' + (lessonStep + 1) + ' of ' + lesson.steps.length;
    $('intro').innerHTML = lessonStep === 0 ? lesson.intro : '';
    $('lesson-title').textContent = s.title;
    $('narration').innerHTML = s.html;
    $('lesson-back').disabled = lessonStep === 0;
    $('lesson-next').disabled = lessonStep === lesson.steps.length - 1;
    document.body.classList.toggle('no-walk', s.walk < 0);
    // The step's figure when it is not the walk: the picture, a cost curve, the tree, a report.
    $('figure-side').hidden = !s.figure;
    $('figure-body').innerHTML = s.figure ? s.figure.html : '';
    $('figure-caption').textContent = s.figure ? s.figure.caption : '';
    if (s.walk >= 0) {
      const r = rayIndex(s.walk, s.ray);
      step = s.step;
      if (current !== rays[r]) {
        $('ray').value = String(r);
        showRay(r);
      }
    }
    const q = s.question;
    quiz.open = Boolean(q) && s.walk >= 0;
    quiz.ray = current;
    quiz.step = s.step;
    document.body.classList.toggle('asking', Boolean(q));  // the figure's answer hidden until then
    const answered = () => {
      quiz.open = false;
      document.body.classList.remove('asking');
      $('answer').hidden = false;
      if (current) go(step, true);
    };
    $('question').hidden = !q;
    $('answer').hidden = true;
    $('verdict').textContent = '';
    $('choices').textContent = '';
    if (q) {
      $('prompt').textContent = q.prompt;
      $('answer-text').textContent = q.answer;
      $('answer-why').textContent = q.why;
      for (const c of q.choices || []) {
        const b = document.createElement('button');
        b.textContent = c.label;
        b.addEventListener('click', () => {
          b.classList.add(c.right ? 'right' : 'wrong');
          $('verdict').textContent = c.right ? 'Right.' : 'Not quite. ' + c.feedback;
          if (c.right) answered();
        });
        $('choices').appendChild(b);
      }
      $('reveal').onclick = answered;
    }
    if (s.walk >= 0) go(s.step, true);
    document.body.dataset.lessonStep = String(lessonStep);
  }

  if (rays.length) showRay(0);
  if (lesson) {
    $('lesson').hidden = false;
    $('ray-choice').hidden = true;  // the lesson picks the ray
    $('lesson-back').addEventListener('click', () => showLessonStep(lessonStep - 1));
    $('lesson-next').addEventListener('click', () => showLessonStep(lessonStep + 1));
    document.addEventListener('keydown', (e) => {
      if (e.key === 'PageDown') { e.preventDefault(); showLessonStep(lessonStep + 1); }
      if (e.key === 'PageUp') { e.preventDefault(); showLessonStep(lessonStep - 1); }
    });
    showLessonStep(0);
  }
  // For scripts and the browser tests: the step shown, and a way to go to one.
  window.raystep = { data, go, get step() { return step; }, ray: (i) => showRay(i), get view3d() { return view3d; },
                     lessonStep: (i) => showLessonStep(i) };
  document.body.dataset.ready = 'true';
})().catch((e) => {
  document.body.dataset.error = String(e);
  document.body.insertAdjacentText('afterbegin', 'raystep player: ' + e);
});
