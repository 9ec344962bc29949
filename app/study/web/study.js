// study.js: the web study's pages (docs/study-api.md). One HTML page, /p/<id>; this script asks the server for the
// participant's state and renders the page the state names (consent, demographics, rating, answers, complete, done)
// into <main>. Each answer is POSTed as one record; the server's reply carries the next state, so the server, not
// this script, decides what comes next (a reload or a restarted server continues at the right page).
'use strict';

(() => {
  const main = document.getElementById('main');
  const progressLine = document.getElementById('progress');
  const statusLine = document.getElementById('status');
  const alertBox = document.getElementById('alert');

  const participant = participantFromPath(location.pathname);
  const apiBase = participant ? `/api/participants/${encodeURIComponent(participant)}` : '';
  // The participant's key (docs/study-api.md, "Keys"): issued by the first begin, kept in the link's fragment (never
  // sent to a server) and in this browser's storage, and sent with every request.
  const keyStorage = `cbtl-study-key:${participant}`;
  let key = keyFromFragment() || storedKey();

  function keyFromFragment() {
    const match = /(?:^#|&)key=([0-9a-f]{64})(?:&|$)/.exec(location.hash);
    return match ? match[1] : '';
  }

  function storedKey() {
    try {
      return localStorage.getItem(keyStorage) || '';
    } catch (e) {
      return '';  // storage refused (a private window): the link still holds the key
    }
  }

  function keepKey(issued) {
    key = issued;
    try {
      localStorage.setItem(keyStorage, issued);
    } catch (e) {
      // the link keeps it
    }
    history.replaceState(null, '', `${location.pathname}${location.search}#key=${issued}`);
  }

  let busy = false;        // a record is being sent: no second submission until it is answered
  let pageShownAt = 0;     // performance.now() when the current page was rendered (for rt_ms)

  // ---------------------------------------------------------------------------------------------------------------
  // Small DOM helpers. Text is always inserted as text nodes, never as HTML, so nothing from the server is markup.

  function el(tag, attrs = {}, ...children) {
    const node = document.createElement(tag);
    for (const [name, value] of Object.entries(attrs)) {
      if (value === undefined || value === null || value === false) continue;
      if (name.startsWith('on')) node.addEventListener(name.slice(2), value);
      else node.setAttribute(name, value === true ? '' : String(value));
    }
    for (const child of children.flat(Infinity)) {
      if (child !== null && child !== undefined) node.append(child);
    }
    return node;
  }

  let idCounter = 0;
  function freshId(prefix) {
    idCounter += 1;
    return `${prefix}-${idCounter}`;
  }

  // A group of native radio buttons in a fieldset, so that the legend is read with each choice and the arrow keys
  // move within the group. items: [{value, text}].
  function radioGroup(name, legend, items, className = '') {
    const choices = items.map((item) =>
      el('label', {class: 'choice'}, el('input', {type: 'radio', name, value: item.value}), el('span', {}, item.text)));
    return el('fieldset', {class: `group ${className}`.trim()}, el('legend', {}, legend),
      el('div', {class: 'choices'}, choices));
  }

  function yesNoGroup(name, legend) {
    return radioGroup(name, legend, [{value: 'yes', text: 'Yes'}, {value: 'no', text: 'No'}], 'yes-no');
  }

  // The checked value of radio group `name` in `form`, or null while none is checked.
  function checkedValue(form, name) {
    const input = form.querySelector(`input[type="radio"][name="${name}"]:checked`);
    return input ? input.value : null;
  }

  function yesNo(form, name) {
    const value = checkedValue(form, name);
    return value === null ? null : value === 'yes';
  }

  // ---------------------------------------------------------------------------------------------------------------
  // Timing. elapsed_ms counts from the first page this tab showed the participant; its start lives in
  // sessionStorage so that a reload keeps counting (performance.now() restarts with the document, so the start is
  // wall-clock time). rt_ms is per page and uses the monotonic performance.now().

  const startKey = `cbtl-study:${participant}:start-ms`;
  const lastKey = `cbtl-study:${participant}:last-elapsed-ms`;
  const memoryStore = {};  // used when sessionStorage is unavailable (some private modes refuse it)

  function storeGet(key) {
    try {
      return sessionStorage.getItem(key);
    } catch (e) {
      return key in memoryStore ? memoryStore[key] : null;
    }
  }

  function storeSet(key, value) {
    try {
      sessionStorage.setItem(key, String(value));
    } catch (e) {
      memoryStore[key] = String(value);
    }
  }

  function markPageShown() {
    pageShownAt = performance.now();
    if (!Number.isFinite(Number.parseFloat(storeGet(startKey)))) storeSet(startKey, Date.now());
  }

  // Never below the last value sent: the wall clock may be set back while the participant takes the study.
  function elapsedMs() {
    const start = Number.parseFloat(storeGet(startKey));
    const since = Number.isFinite(start) ? Math.round(Date.now() - start) : 0;
    const last = Number.parseInt(storeGet(lastKey) || '0', 10) || 0;
    const elapsed = Math.max(0, since, last);
    storeSet(lastKey, elapsed);
    return elapsed;
  }

  function rtMs() {
    return Math.max(0, Math.round(performance.now() - pageShownAt));
  }

  // ---------------------------------------------------------------------------------------------------------------
  // Talking to the server.

  function participantFromPath(path) {
    const match = /^\/p\/([A-Za-z0-9_.-]{1,64})\/?$/.exec(path);
    return match ? match[1] : null;
  }

  function sleep(ms) {
    return new Promise((resolve) => setTimeout(resolve, ms));
  }

  // One request. Resolves to {ok, status, data} for any HTTP answer; rejects only when the answer was lost (no
  // connection, or an OK answer whose body did not arrive whole), which is what makes resending the same body
  // the right reaction.
  async function requestOnce(method, path, body) {
    const init = {method, headers: {Accept: 'application/json'}, cache: 'no-store'};
    if (key) init.headers.Authorization = `Bearer ${key}`;
    if (body !== undefined) {
      init.headers['Content-Type'] = 'application/json';
      init.body = JSON.stringify(body);
    }
    const response = await fetch(path, init);
    const retryAfter = Number(response.headers.get('Retry-After')) || 0;
    let data = null;
    try {
      data = await response.json();
    } catch (e) {
      if (response.ok) throw e;  // an OK answer cut short: treat it as lost
    }
    return {ok: response.ok, status: response.status, data, retryAfter};
  }

  // Resends the very same body until some HTTP answer arrives. The server answers a repeated record "replayed"
  // without storing it twice, so resending after a lost answer is harmless.
  async function request(method, path, body) {
    let delay = 1000;
    for (;;) {
      try {
        const result = await requestOnce(method, path, body);
        setStatus('');
        return result;
      } catch (e) {
        setStatus(`The study's server cannot be reached. Trying again in ${Math.round(delay / 1000)} s…`);
        await sleep(delay);
        delay = Math.min(delay * 2, 10000);
      }
    }
  }

  function errorMessage(result) {
    if (result.data && typeof result.data.error === 'string' && result.data.error) return result.data.error;
    return `The server answered with HTTP status ${result.status}.`;
  }

  function setStatus(text) {
    statusLine.textContent = text;
  }

  function showAlert(text) {
    alertBox.textContent = text;
    alertBox.scrollIntoView({block: 'nearest'});
  }

  function clearAlert() {
    alertBox.textContent = '';
  }

  // ---------------------------------------------------------------------------------------------------------------
  // Words shown to the participant.

  // The display word for a value the server names (e.g. "bbqSauce" -> "BBQ sauce"); the raw value when the state's
  // labels do not name it.
  function word(state, value) {
    const labels = state.labels || {};
    return Object.prototype.hasOwnProperty.call(labels, value) ? labels[value] : String(value);
  }

  function joinWithAnd(words) {
    if (words.length <= 1) return words.join('');
    return `${words.slice(0, -1).join(', ')} and ${words[words.length - 1]}`;
  }

  // "Meal 2 of 5: raw vegetables with hummus and ranch, with a friend, at a circular table"
  function mealContext(state) {
    const context = state.context || {};
    const sauces = (context.sauces || []).map((sauce) => word(state, sauce));
    const parts = [];
    if (context.food) parts.push(sauces.length ? `${context.food} with ${joinWithAnd(sauces)}` : context.food);
    const setting = context.setting_text || (context.setting ? word(state, context.setting) : '');
    if (setting) parts.push(setting);
    if (context.table) parts.push(`at a ${word(state, context.table)} table`);
    return `Meal ${state.meal} of ${state.meals || 5}: ${parts.join(', ')}`;
  }

  function totalPages(state) {
    if (Number.isInteger(state.pages)) return state.pages;
    return 3 + 2 * (state.meals || 5);  // consent, demographics, two pages per meal, complete
  }

  // ---------------------------------------------------------------------------------------------------------------
  // Showing a page.

  // Replaces the page's content, moves focus to its heading (so a screen reader announces the new page and the
  // keyboard starts from its top) and starts the page's response time.
  function show(state, title, content, progressText) {
    const heading = el('h1', {id: 'page-heading', tabindex: '-1'}, title);
    main.replaceChildren(heading, ...content);
    main.dataset.page = state.page;
    progressLine.textContent =
      progressText || `Page ${Math.min(state.next_trial + 1, totalPages(state))} of ${totalPages(state)}`;
    clearAlert();
    setStatus('');
    window.scrollTo(0, 0);
    heading.focus();
    markPageShown();
  }

  // A page with questions: `page.response()` gives the answer to send, or null while a required answer is missing;
  // the Continue button stays disabled until then.
  function showForm(state, page) {
    const hintId = freshId('hint');
    const button = el('button', {type: 'submit', class: 'primary', 'aria-describedby': hintId},
      page.buttonText || 'Continue');
    const hint = el('p', {id: hintId, class: 'hint'}, 'Please answer every question to continue.');
    const form = el('form', {novalidate: true}, page.content, el('div', {class: 'actions'}, button, hint));

    const refresh = () => {
      const complete = page.response(form) !== null;
      button.disabled = busy || !complete;
      hint.hidden = complete;
    };
    form.addEventListener('input', refresh);
    form.addEventListener('change', refresh);
    form.addEventListener('submit', (event) => {
      event.preventDefault();
      const response = page.response(form);
      if (busy || response === null) return;
      if (page.submit) page.submit(response, refresh);
      else sendRecord(state, response, refresh);
    });

    show(state, page.title, [form]);
    refresh();
  }

  // Sends the page's record and renders the state the server answers; an HTTP error leaves the page (and its
  // answers) as it is, with the server's message in the alert region.
  async function sendRecord(state, response, refresh) {
    const rt = rtMs();  // measured at the click, before anything else takes time
    const body = {
      trial_index: state.next_trial, kind: state.page, meal: state.meal,
      elapsed_ms: elapsedMs(), rt_ms: rt, response,
    };
    busy = true;
    refresh();
    clearAlert();
    setStatus('Saving your answers…');
    const result = await request('POST', `${apiBase}/records`, body);
    busy = false;
    if (result.ok && result.data && result.data.state) {
      render(result.data.state);
      return;
    }
    setStatus('');
    let message = `Your answer could not be saved: ${errorMessage(result)}`;
    if (result.status === 409) message += ' If the study is open in another window, reload this page to continue.';
    showAlert(message);
    refresh();
  }

  // ---------------------------------------------------------------------------------------------------------------
  // The pages.

  // Who runs the study, as the study-info file says (cbtl study serve --study-info): only the fields it gives.
  function studyContacts(study) {
    const rows = [['Researcher', study.researcher], ['Institution', study.institution], ['Contact', study.contact],
      ['Ethics approval', study.ethics_approval]].filter(([, value]) => typeof value === 'string' && value !== '');
    if (!rows.length) return [];
    return [el('dl', {class: 'study-info'},
      rows.map(([name, value]) => el('div', {}, el('dt', {}, name), el('dd', {}, value))))];
  }

  function consentPage(state) {
    const study = state.study || {};
    const paragraphs = Array.isArray(study.consent) && study.consent.length ? study.consent : [
      'This study is about a robot arm that helps a person eat. We would like to learn which of ' +
        'the robot\'s choices you would want if it were feeding you.',
      'You will see five meals, one after the other. For each meal you compare two ways the robot ' +
        'could serve it, then tell us what you would want yourself and whether the arm would be in your way ' +
        'in a few pictures.',
      'It takes about 10 to 15 minutes.',
      'We do not ask for your name or any contact details: your answers are stored under an ' +
        'anonymous id. Taking part is voluntary, and you may stop at any time by closing this window.',
    ];
    showForm(state, {
      title: typeof study.title === 'string' && study.title ? study.title : 'Taking part in this study',
      content: [
        ...paragraphs.map((text) => el('p', {}, text)),
        ...studyContacts(study),
        radioGroup('consent', 'Do you agree to take part?',
          [{value: 'agree', text: 'I agree'}, {value: 'decline', text: 'I do not agree'}]),
      ],
      response: (form) => {
        const value = checkedValue(form, 'consent');
        return value === null ? null : {agree: value === 'agree'};
      },
      // Declining is not a record: the participant simply leaves.
      submit: (response, refresh) => (response.agree ? sendRecord(state, response, refresh) : declinedPage(state)),
    });
  }

  function declinedPage(state) {
    const back = el('button', {type: 'button', class: 'secondary', onclick: () => consentPage(state)},
      'I changed my mind');
    show({...state, page: 'declined'}, 'Thank you for your time', [
      el('p', {}, 'You chose not to take part, so nothing about you has been recorded.'),
      el('p', {class: 'closing'}, 'You may close this window now.'),
      el('p', {}, 'If you chose this by mistake, you can go back:'),
      back,
    ]);
  }

  function demographicsPage(state) {
    const ageId = freshId('age');
    const ageHintId = freshId('age-hint');
    const age = el('input', {id: ageId, type: 'number', name: 'age', min: 18, max: 120, step: 1,
      inputmode: 'numeric', autocomplete: 'off', 'aria-describedby': ageHintId});
    const ageHint = el('p', {id: ageHintId, class: 'hint'}, 'A whole number from 18 to 120.');
    const noAge = el('input', {type: 'checkbox', name: 'age-not-said'});
    noAge.addEventListener('change', () => {
      age.disabled = noAge.checked;  // the two answers exclude each other
    });

    const otherId = freshId('gender-other');
    const other = el('input', {id: otherId, type: 'text', name: 'gender-other', maxlength: 100, disabled: true,
      autocomplete: 'off'});
    const gender = radioGroup('gender', 'Gender', [
      {value: 'male', text: 'Male'}, {value: 'female', text: 'Female'}, {value: 'non-binary', text: 'Non-binary'},
      {value: 'prefer-not-to-say', text: 'Prefer not to say'}, {value: 'other', text: 'Other'},
    ]);
    gender.append(el('div', {class: 'other-field'},
      el('label', {for: otherId}, 'If other, how would you describe it? (optional)'), other));
    gender.addEventListener('change', () => {
      other.disabled = checkedValue(gender, 'gender') !== 'other';
    });

    showForm(state, {
      title: 'About you',
      content: [
        el('p', {}, 'A few questions about you, so that we can describe who took part.'),
        el('fieldset', {class: 'group'}, el('legend', {}, 'Age'),
          el('label', {for: ageId}, 'Your age in years'), age, ageHint,
          el('label', {class: 'choice'}, noAge, el('span', {}, 'I prefer not to say'))),
        gender,
        yesNoGroup('robot', 'Have you interacted with a robot before?'),
        yesNoGroup('fed', 'Have you ever been fed by another person or a device as an adult?'),
      ],
      response: (form) => {
        const ageValue = noAge.checked ? null : parseAge(age.value);
        if (!noAge.checked && ageValue === null) return null;
        const genderValue = checkedValue(form, 'gender');
        const robot = yesNo(form, 'robot');
        const fed = yesNo(form, 'fed');
        if (genderValue === null || robot === null || fed === null) return null;
        return {
          age: ageValue, gender: genderValue, gender_other: genderValue === 'other' ? other.value.trim() : '',
          robot_experience: robot, fed_experience: fed,
        };
      },
    });
  }

  // The typed age, or null when it is not a whole number from 18 to 120.
  function parseAge(text) {
    if (!/^\s*\d{1,3}\s*$/.test(text)) return null;
    const age = Number.parseInt(text, 10);
    return age >= 18 && age <= 120 ? age : null;
  }

  function optionCard(state, option) {
    const title = `Option ${option.label}`;
    if (!option.solved) {
      return el('section', {class: 'option unsolved', 'aria-label': title}, el('h3', {}, title),
        el('p', {}, 'The robot found no plan for this meal, so it could not feed you.'));
    }
    const row = (name, value) => el('div', {}, el('dt', {}, name), el('dd', {}, word(state, value)));
    return el('section', {class: 'option', 'aria-label': title}, el('h3', {}, title),
      el('dl', {}, row('Dip', option.dip), row('Ready signal', option.signal), row('Talking', option.verbosity)));
  }

  const likertItems = [
    {value: '1', text: 'Strongly prefer A'}, {value: '2', text: 'Prefer A'}, {value: '3', text: 'No preference'},
    {value: '4', text: 'Prefer B'}, {value: '5', text: 'Strongly prefer B'},
  ];

  // Whether the two options would feed the participant alike (then the rating page says why).
  function sameOptions(options) {
    if (!options || options.length !== 2 || !options[0].solved || !options[1].solved) return false;
    return ['dip', 'signal', 'verbosity'].every((key) => options[0][key] === options[1][key]);
  }

  function ratingPage(state) {
    const same = sameOptions(state.options);
    const why = same ? el('p', {class: 'hint'}, state.meal === 1 ?
      'The two options are the same this time: this is your first meal, so the robot has not learned anything ' +
        'about you yet. It learns from your answers after each meal. If they look the same to you, choose ' +
        '"No preference".' :
      'The two options are the same this time. If they look the same to you, choose "No preference".') : null;
    showForm(state, {
      title: mealContext(state),
      content: [
        el('h2', {}, 'Two ways the robot could feed you'),
        el('p', {}, 'Imagine the robot feeding you this meal. The ready signal is how you let it know you are ' +
          'ready for the next bite; "talking" is how much it speaks while it feeds you.'),
        ...(why ? [why] : []),
        el('div', {class: 'options'}, (state.options || []).map((option) => optionCard(state, option))),
        radioGroup('likert', 'Which option would you prefer?', likertItems, 'likert'),
      ],
      response: (form) => {
        const value = checkedValue(form, 'likert');
        return value === null ? null : {likert: Number(value)};
      },
    });
  }

  // What the arm could block, from the meal's company: the TV, the friend, or (alone) the table and the plate.
  function viewOf(state) {
    const setting = (state.context || {}).setting;
    if (setting === 'withFriendAndTv') return 'your view of your friend or of the TV';
    if (setting === 'withFriend') return 'your view of your friend';
    if (setting === 'withTv') return 'your view of the TV';
    return 'your view of the table and your plate';
  }

  // A picture needs the key too, so it is fetched with it and shown from memory (a blob: address).
  async function loadPicture(image, url, failed) {
    try {
      const response = await fetch(url, {headers: key ? {Authorization: `Bearer ${key}`} : {}, cache: 'no-store'});
      if (!response.ok) throw new Error(`HTTP ${response.status}`);
      image.src = URL.createObjectURL(await response.blob());
    } catch (e) {
      failed.hidden = false;
    }
  }

  function pictureQuestion(url, index, count, state) {
    const title = `Picture ${index + 1} of ${count}`;
    const image = el('img', {class: 'view',
      alt: `${title}: the robot arm above your plate, seen from where you sit`});
    const failed = el('p', {class: 'hint', hidden: true},
      'This picture did not load. Please reload the page to try again.');
    image.addEventListener('error', () => {
      failed.hidden = false;
    });
    loadPicture(image, url, failed);
    return el('section', {class: 'picture'}, el('h3', {}, title), el('figure', {}, image), failed,
      yesNoGroup(`blocked-${index}`, `Would the robot arm here block ${viewOf(state)}?`));
  }

  function answersPage(state) {
    const choices = state.choices || {};
    const items = (values) => (values || []).map((value) => ({value, text: word(state, value)}));
    const views = state.views || [];
    showForm(state, {
      title: mealContext(state),
      content: [
        el('h2', {}, 'What would you want?'),
        el('p', {}, 'Leaving the two options aside: how would you like the robot to feed you this meal?'),
        radioGroup('dip', 'Which dip would you like?', items(choices.dip)),
        radioGroup('signal', 'How would you like to tell the robot you are ready for the next bite?',
          items(choices.signal)),
        radioGroup('verbosity', 'How much should the robot talk while it feeds you?', items(choices.verbosity)),
        views.length ? el('h2', {}, 'The arm, seen from your seat') : null,
        views.length ? el('p', {}, 'Each picture shows where the robot arm could wait above your plate, seen ' +
          'from where you sit.') : null,
        views.map((url, index) => pictureQuestion(url, index, views.length, state)),
      ],
      response: (form) => {
        const dip = checkedValue(form, 'dip');
        const signal = checkedValue(form, 'signal');
        const verbosity = checkedValue(form, 'verbosity');
        const blocked = views.map((url, index) => yesNo(form, `blocked-${index}`));
        if (dip === null || signal === null || verbosity === null || blocked.includes(null)) return null;
        return {dip, signal, verbosity, blocked};
      },
    });
  }

  function completePage(state) {
    const commentsId = freshId('comments');
    const comments = el('textarea', {id: commentsId, name: 'comments', maxlength: 2000, rows: 6});
    showForm(state, {
      title: 'Thank you!',
      buttonText: 'Submit',
      content: [
        el('p', {}, 'You have been through all five meals. If you would like to tell us anything about the ' +
          'study or the robot, you can write it here.'),
        el('label', {for: commentsId}, 'Comments (optional)'),
        comments,
      ],
      response: () => ({comments: comments.value}),
    });
  }

  function donePage(state) {
    show(state, 'All done: thank you for taking part', [
      el('p', {}, 'Your answers have been saved. There is nothing more to do.'),
      el('p', {class: 'closing'}, 'You may close this window now.'),
    ], `All ${totalPages(state)} pages done`);
  }

  function fatalPage(message) {
    main.replaceChildren(el('h1', {id: 'page-heading', tabindex: '-1'}, 'The study cannot be shown'),
      el('p', {}, message));
    main.dataset.page = 'error';
    progressLine.textContent = '';
    showAlert(message);
    main.querySelector('h1').focus();
  }

  const pages = {
    consent: consentPage, demographics: demographicsPage, rating: ratingPage, answers: answersPage,
    complete: completePage, done: donePage,
  };

  function render(state) {
    const page = pages[state.page];
    if (!page) {
      fatalPage(`The server asked for a page this script does not know ("${state.page}").`);
      return;
    }
    page(state);
  }

  // Begins (or continues) the participant named by the address and shows their next page.
  async function begin() {
    if (!participant) {
      fatalPage('This address does not name a participant. Please use the exact link you were given.');
      return;
    }
    let result = await request('POST', apiBase, {});
    // Many people joining at once: the server says when to come back.
    while (result.status === 429) {
      const seconds = Math.max(1, result.retryAfter || 5);
      setStatus(`Many people are joining the study right now. You will be let in in ${seconds} s…`);
      await sleep(seconds * 1000);
      result = await request('POST', apiBase, {});
    }
    setStatus('');
    if (result.ok && result.data && typeof result.data.key === 'string') keepKey(result.data.key);
    if (result.ok && result.data && result.data.page) render(result.data);
    else fatalPage(errorMessage(result));
  }

  begin();
})();
