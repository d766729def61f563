// slamcourse in the browser: sends answers to the engine and shows what it returns.
// No grading happens here. Learner text is only ever set with textContent; HTML comes from the
// server, which renders Markdown with raw HTML disabled.
"use strict";

(function () {
  // The marks and words of exercise states come from the page's legend, which the server fills
  // from the engine's one table of them (the terminal's `list` shows the same).
  const MARK = {};
  const WORD = {};
  document.querySelectorAll("[data-legend-mark]").forEach(function (el) {
    MARK[el.dataset.legendMark] = el.textContent;
    WORD[el.dataset.legendMark] = el.dataset.word;
  });
  const STATUS = {
    passed: "✓ Correct",
    failed: "✗ Not yet",
    invalid: "? Could not read that",
    timeout: "⏱ Took too long",
    error: "! Grader error",
  };

  // ------------------------------------------------------------------ math
  function typeset(root) {
    if (!window.katex) return;
    root.querySelectorAll(".math").forEach(function (el) {
      if (el.dataset.typeset) return;
      const tex = el.textContent;
      el.dataset.typeset = "1";
      el.setAttribute("data-tex", tex);
      window.katex.render(tex, el, {
        displayMode: el.classList.contains("block"),
        throwOnError: false,
        output: "htmlAndMathml",
      });
    });
  }

  // Server-rendered, escaped HTML (never learner text) into an element.
  function setHTML(el, html) {
    const doc = new DOMParser().parseFromString("<body>" + (html || "") + "</body>", "text/html");
    el.replaceChildren(...Array.from(doc.body.childNodes));
    typeset(el);
  }

  // ------------------------------------------------------------------ requests
  async function post(url, body) {
    const resp = await fetch(url, {
      method: "POST",
      headers: { "Content-Type": "application/json" },
      body: JSON.stringify(body || {}),
      credentials: "same-origin",
    });
    let data = null;
    try {
      data = await resp.json();
    } catch (e) {
      data = { error: "The server answered " + resp.status + "." };
    }
    if (!resp.ok && !data.error) data.error = "The server answered " + resp.status + ".";
    return data;
  }

  async function get(url) {
    const resp = await fetch(url, { credentials: "same-origin" });
    return resp.json();
  }

  // Where the app is mounted: "" on its own port, the proxy's prefix behind a hub
  // (jupyter-server-proxy); the server says which in the page.
  const rootMeta = document.querySelector('meta[name="slamcourse-root"]');
  const ROOT = rootMeta ? rootMeta.content : "";

  function api(kind, id) {
    return ROOT + "/api/" + kind + "/" + id.split("/").map(encodeURIComponent).join("/");
  }

  // ------------------------------------------------------------------ sidebar
  function setBar(bar, solved, total) {
    if (!bar) return;
    bar.max = total;
    bar.value = solved;
    bar.textContent = solved + "/" + total;
  }

  function refreshSidebar(summary) {
    if (!summary) return;
    let solvedAll = 0;
    let totalAll = 0;
    summary.forEach(function (ch) {
      solvedAll += ch.solved;
      totalAll += ch.total;
      const count = document.querySelector('[data-count="' + CSS.escape(ch.id) + '"]');
      if (count) count.textContent = ch.solved + "/" + ch.total;
      setBar(document.querySelector('[data-bar="' + CSS.escape(ch.id) + '"]'), ch.solved, ch.total);
      ch.exercises.forEach(function (ex) {
        const li = document.querySelector('[data-status-of="' + CSS.escape(ex.id) + '"]');
        if (!li) return;
        const shown = ex.status === "pending" && ex.skipped ? "skipped" : ex.status;
        li.className = "status-" + ex.status;
        li.querySelector(".mark").textContent = MARK[shown];
        li.querySelector(".word").textContent = WORD[shown];
      });
    });
    const overall = document.querySelector("[data-overall]");
    if (overall) overall.textContent = solvedAll + "/" + totalAll;
    setBar(document.querySelector("[data-overall-bar]"), solvedAll, totalAll);
  }

  function setStatus(section, status) {
    section.classList.remove("status-pending", "status-solved", "status-given_up");
    section.classList.add("status-" + status);
    section.querySelector("[data-badge]").textContent = MARK[status] + " " + WORD[status];
    section.querySelector("[data-giveup]").hidden = status !== "pending";  // nothing to give up
  }

  // ------------------------------------------------------------------ answers
  function cellsOf(form) {
    return Array.from(form.querySelectorAll("[data-cell]"));
  }

  function answerText(section) {
    const form = section.querySelector("[data-answer]");
    const type = section.dataset.form;
    if (type === "number" || type === "expression") {
      return form.querySelector("[data-input]").value.trim();
    }
    if (type === "vector") {
      return "[" + cellsOf(form).map((c) => c.value.trim()).join(", ") + "]";
    }
    if (type === "matrix") {
      const rows = [];
      cellsOf(form).forEach(function (c) {
        const ij = c.dataset.cell.split(",").map(Number);
        (rows[ij[0]] = rows[ij[0]] || [])[ij[1]] = c.value.trim();
      });
      return "[" + rows.map((r) => "[" + r.join(", ") + "]").join(", ") + "]";
    }
    if (type === "multi") {
      return Array.from(form.querySelectorAll('[data-toggle][aria-pressed="true"]'))
        .map((b) => b.dataset.toggle)
        .join(" ");
    }
    if (type === "order") {
      return Array.from(form.querySelectorAll("[data-item]"))
        .map((li) => li.dataset.item)
        .join(" ");
    }
    return "";
  }

  function markCells(section, result) {
    const form = section.querySelector("[data-answer]");
    const cells = cellsOf(form);
    cells.forEach(function (c) {
      c.classList.remove("wrong", "right");
      c.removeAttribute("aria-invalid");
    });
    if (!cells.length || result.status === "invalid") return;
    const wrong = new Set(((result.details || {}).wrong || []).map((w) => w.join(",")));
    cells.forEach(function (c) {
      if (wrong.has(c.dataset.cell)) {
        c.classList.add("wrong");
        c.setAttribute("aria-invalid", "true");
      } else if (result.status === "passed" || wrong.size) {
        c.classList.add("right");
      }
    });
  }

  function showTests(section, result) {
    const box = section.querySelector("[data-tests]");
    box.replaceChildren();
    (result.tests || []).forEach(function (t) {
      if (t.status === "passed") return;
      const table = document.createElement("table");
      table.className = "counterexample";
      const cap = document.createElement("caption");
      cap.textContent = "Smallest failing input";
      table.appendChild(cap);
      const rows = [];
      Object.keys(t.input || {}).forEach(function (k) {
        rows.push([k, JSON.stringify(t.input[k])]);
      });
      rows.push(["expected", JSON.stringify(t.expected)]);
      rows.push(["your function returned", t.got === undefined ? "(nothing)" : JSON.stringify(t.got)]);
      rows.forEach(function (r) {
        const tr = document.createElement("tr");
        const th = document.createElement("th");
        th.scope = "row";
        th.textContent = r[0];
        const td = document.createElement("td");
        const code = document.createElement("code");
        code.textContent = r[1];
        td.appendChild(code);
        tr.append(th, td);
        table.appendChild(tr);
      });
      box.appendChild(table);
    });
  }

  function showResult(section, result) {
    const fb = section.querySelector("[data-feedback]");
    fb.className = "feedback";
    if (result.error) {
      fb.classList.add("is-error");
      fb.replaceChildren();
      const p = document.createElement("p");
      p.textContent = "! " + result.error;
      fb.appendChild(p);
      return;
    }
    fb.classList.add("is-" + result.status);
    const head = document.createElement("p");
    head.className = "verdict";
    head.textContent = STATUS[result.status] || result.status;
    if (result.practice) head.textContent += " (practice: not counted)";
    else if (!result.counted && result.status !== "passed") head.textContent += " (no attempt used)";
    const body = document.createElement("div");
    setHTML(body, result.feedback_html);
    fb.replaceChildren(head, body);
    if (result.nudge_html) {
      const n = document.createElement("div");
      n.className = "nudge";
      setHTML(n, result.nudge_html);
      fb.appendChild(n);
    }
    if (result.next_url && result.status === "passed" && !result.practice) {
      if (result.next_note_html) {  // the engine's word on where next goes (wrapped, skipped)
        const note = document.createElement("p");
        note.className = "next-note";
        setHTML(note, result.next_note_html);
        fb.appendChild(note);
      }
      const a = document.createElement("a");
      a.className = "button primary";
      a.href = result.next_url;
      a.textContent = "Next exercise →";
      fb.appendChild(a);
    }
    markCells(section, result);
    showTests(section, result);
    if (result.explanation_html) showExplanation(section, result.explanation_html);
    showPlot(section, result.plot_svg);
    if (!result.practice) {
      setStatus(section, result.exercise_status);
      const at = section.querySelector("[data-attempts]");
      at.textContent = result.attempts + (result.attempts === 1 ? " attempt" : " attempts");
    }
    refreshSidebar(result.summary);
  }

  // Our own SVG (numbers and fixed labels, text escaped by the server) into the figure.
  function showPlot(section, svg) {
    if (!svg) return;
    const fig = section.querySelector("[data-plot]");
    const doc = new DOMParser().parseFromString(svg, "image/svg+xml");
    fig.replaceChildren(document.importNode(doc.documentElement, true));
    fig.hidden = false;
  }

  function showExplanation(section, html) {
    const box = section.querySelector("[data-explanation]");
    setHTML(box.querySelector("[data-explanation-body]"), html);
    box.hidden = false;
  }

  function busy(section, on) {
    section.setAttribute("aria-busy", on ? "true" : "false");
    section.querySelectorAll("[data-answer] button").forEach((b) => (b.disabled = on));
  }

  // ``base``: the content hash of the file's version this text replaces (the one the page
  // loaded, or the one a conflict showed when the learner keeps their text).
  async function submit(section, answer, base) {
    const id = section.dataset.exercise;
    busy(section, true);
    let result;
    try {
      if (section.dataset.form === "code") {
        const area = section.querySelector("[data-code]");
        const fb = section.querySelector("[data-feedback]");
        fb.className = "feedback";
        fb.textContent = "Running your code in the sandbox…";
        result = await post(api("code", id), {
          source: area.value,
          based_on: base || area.dataset.hash,
        });
        if (result.file_hash) area.dataset.hash = result.file_hash;
        if (result.conflict) {
          busy(section, false);
          return showConflict(section, result.conflict);
        }
      } else {
        const canonical = !!(section.querySelector("[data-practice]") || {}).checked;
        result = await post(api("answer", id), { answer: answer, canonical: canonical });
      }
    } catch (e) {
      result = { error: "No answer from the server (is `slamcourse serve` still running?)." };
    }
    busy(section, false);
    showResult(section, result);
  }

  // ------------------------------------------------------------------ formulas
  const GREEK = new Set(["alpha", "beta", "gamma", "delta", "epsilon", "theta", "lambda", "mu",
    "nu", "pi", "rho", "sigma", "tau", "phi", "psi", "omega", "Delta", "Sigma", "Phi", "Omega"]);
  const KNOWN_FN = new Set(["sin", "cos", "tan", "exp", "log", "arcsin", "arccos", "arctan",
    "max", "min"]);

  function tokens(s) {
    const out = [];
    const re = /\s*(\d+\.?\d*(?:[eE][-+]?\d+)?|\.\d+|[A-Za-z_][A-Za-z_0-9]*|\*\*|[-+*/^(),])/y;
    let m;
    let i = 0;
    while (i < s.length) {
      re.lastIndex = i;
      m = re.exec(s);
      if (!m) {
        if (/^\s*$/.test(s.slice(i))) break;
        throw new Error("unexpected " + s[i]);
      }
      out.push(m[1]);
      i = re.lastIndex;
    }
    return out;
  }

  function strip(t) {
    return t.paren ? t.inner : t.tex;
  }

  function ident(name) {
    if (GREEK.has(name)) return "\\" + name;
    const m = /^([A-Za-z]+)_?(\d+)$/.exec(name);
    if (m) return ident(m[1]) + "_{" + m[2] + "}";
    if (name.length === 1) return name;
    if (/^d[a-z]$/.test(name)) return "\\Delta " + name[1];
    return "\\mathit{" + name.replace(/_/g, "\\_") + "}";
  }

  function toLatex(src) {
    const ts = tokens(src);
    let p = 0;
    const peek = () => ts[p];
    const eat = (t) => {
      if (ts[p] !== t) throw new Error("expected " + t);
      p++;
    };
    function expr() {
      let left = term();
      while (peek() === "+" || peek() === "-") {
        const op = ts[p++];
        const right = term();
        left = { tex: left.tex + " " + op + " " + right.tex };
      }
      return left;
    }
    function term() {
      let left = unary();
      while (peek() === "*" || peek() === "/") {
        const op = ts[p++];
        const right = unary();
        left = op === "/"
          ? { tex: "\\frac{" + strip(left) + "}{" + strip(right) + "}" }
          : { tex: left.tex + " \\cdot " + right.tex };
      }
      return left;
    }
    function unary() {
      if (peek() === "-") {
        p++;
        return { tex: "-" + unary().tex };
      }
      if (peek() === "+") {
        p++;
        return unary();
      }
      return power();
    }
    function power() {
      const base = atom();
      if (peek() === "^" || peek() === "**") {
        p++;
        const ex = unary();
        return { tex: "{" + base.tex + "}^{" + strip(ex) + "}" };
      }
      return base;
    }
    function atom() {
      const t = ts[p++];
      if (t === undefined) throw new Error("unfinished");
      if (t === "(") {
        const inner = expr();
        eat(")");
        return { tex: "\\left(" + inner.tex + "\\right)", paren: true, inner: inner.tex };
      }
      if (/^[\d.]/.test(t)) return { tex: t };
      if (/^[A-Za-z_]/.test(t)) {
        if (peek() === "(") {
          p++;
          const args = [];
          if (peek() !== ")") {
            args.push(expr().tex);
            while (peek() === ",") {
              p++;
              args.push(expr().tex);
            }
          }
          eat(")");
          const a = args.join(", ");
          if (t === "sqrt") return { tex: "\\sqrt{" + a + "}" };
          if (t === "abs") return { tex: "\\left|" + a + "\\right|" };
          const name = KNOWN_FN.has(t) ? "\\" + t : "\\operatorname{" + t + "}";
          return { tex: name + "\\left(" + a + "\\right)" };
        }
        return { tex: ident(t) };
      }
      throw new Error("unexpected " + t);
    }
    const out = expr();
    if (p !== ts.length) throw new Error("unexpected " + ts[p]);
    return out.tex;
  }

  function preview(input, box) {
    const text = input.value.trim();
    box.replaceChildren();
    if (!text) return;
    try {
      const tex = toLatex(text);
      window.katex.render(tex, box, { throwOnError: false, displayMode: true });
      box.classList.remove("unfinished");
    } catch (e) {
      box.classList.add("unfinished");
      box.textContent = "… " + text;
    }
  }

  // ------------------------------------------------------------------ code editor
  const editors = new WeakMap(); // textarea -> CodeMirror view

  function setCode(area, text) {
    const view = editors.get(area);
    if (view) view.dispatch({ changes: { from: 0, to: view.state.doc.length, insert: text } });
    else {
      area.value = text;
      area.dispatchEvent(new Event("input"));
    }
  }

  // The file changed on disk since the page loaded it: nothing was written or graded. The
  // engine's message, and the learner's two choices.
  function showConflict(section, conflict) {
    const fb = section.querySelector("[data-feedback]");
    fb.className = "feedback is-conflict";
    const p = document.createElement("p");
    p.className = "verdict";
    p.textContent = "! " + conflict.message;
    const load = document.createElement("button");
    load.type = "button";
    load.dataset.loadDisk = "";
    load.textContent = "Load the file's version";
    const keep = document.createElement("button");
    keep.type = "button";
    keep.dataset.keepMine = "";
    keep.textContent = "Keep mine (overwrite " + conflict.name + ")";
    const area = section.querySelector("[data-code]");
    load.addEventListener("click", function () {
      setCode(area, conflict.disk_source);
      area.dataset.hash = conflict.disk_hash;
      announce(section, "Loaded " + conflict.name + " from disk. Check it when you are ready.");
    });
    keep.addEventListener("click", function () {
      submit(section, null, conflict.disk_hash);
    });
    const choices = document.createElement("p");
    choices.className = "choices";
    choices.append(load, " ", keep);
    fb.replaceChildren(p, choices);
    load.focus();
  }

  function gutter(area, pre) {
    const n = area.value.split("\n").length;
    const lines = [];
    for (let i = 1; i <= n; i++) lines.push(String(i));
    pre.textContent = lines.join("\n");
    area.rows = Math.max(8, n + 1);
  }

  // Tab in the editor: by default it moves on to the next control like everywhere else on the
  // page (no keyboard trap); Ctrl+M switches Tab to indenting and back (CodeMirror's own key
  // for this), and while it indents, Esc then Tab still leaves. The help line says which.
  const TAB_LEAVES = "Tab moves on to the next control. Press Ctrl+M in the editor to make Tab " +
    "indent (Enter keeps the indentation; Ctrl+] and Ctrl+[ indent and dedent).";
  const TAB_INDENTS = "Tab indents by 4 spaces; Esc then Tab leaves the editor. Press Ctrl+M " +
    "to make Tab move on to the next control again.";

  function isTabModeKey(ev) {
    return ev.ctrlKey && !ev.altKey && !ev.metaKey && !ev.shiftKey && (ev.key === "m" || ev.key === "M");
  }

  function setTabIndents(section, area, indents) {
    if (indents) area.dataset.tabIndents = "1";
    else delete area.dataset.tabIndents;
    const help = section.querySelector("[data-editor-help]");
    if (help) help.textContent = indents ? TAB_INDENTS : TAB_LEAVES;
  }

  function editorKeys(section, area, ev) {
    if (isTabModeKey(ev)) {
      ev.preventDefault();
      setTabIndents(section, area, !area.dataset.tabIndents);
      return;
    }
    if (ev.key === "Escape") {
      area.dataset.escaped = "1";
      return;
    }
    if (ev.key !== "Tab" || area.dataset.escaped || !area.dataset.tabIndents) {
      delete area.dataset.escaped;
      return;
    }
    ev.preventDefault();
    const s = area.selectionStart;
    const e = area.selectionEnd;
    const v = area.value;
    if (ev.shiftKey) {
      const lineStart = v.lastIndexOf("\n", s - 1) + 1;
      const cut = v.slice(lineStart, lineStart + 4).match(/^ {0,4}/)[0].length;
      area.value = v.slice(0, lineStart) + v.slice(lineStart + cut);
      area.selectionStart = area.selectionEnd = Math.max(lineStart, s - cut);
    } else {
      area.value = v.slice(0, s) + "    " + v.slice(e);
      area.selectionStart = area.selectionEnd = s + 4;
    }
    area.dispatchEvent(new Event("input"));
  }

  // ------------------------------------------------------------------ ordering
  function moveItem(li, delta) {
    const list = li.parentElement;
    if (delta < 0 && li.previousElementSibling) list.insertBefore(li, li.previousElementSibling);
    if (delta > 0 && li.nextElementSibling) list.insertBefore(li.nextElementSibling, li);
    li.focus();
    announce(li.closest("section"), li.querySelector(".item-text").textContent + ": position " +
      (Array.from(list.children).indexOf(li) + 1) + " of " + list.children.length);
  }

  function announce(section, text) {
    const fb = section.querySelector("[data-feedback]");
    fb.className = "feedback";
    fb.textContent = text;
  }

  function setupOrder(list) {
    let dragged = null;
    list.addEventListener("dragstart", function (ev) {
      dragged = ev.target.closest("[data-item]");
      ev.dataTransfer.effectAllowed = "move";
      ev.dataTransfer.setData("text/plain", dragged.dataset.item);
      dragged.classList.add("dragging");
    });
    list.addEventListener("dragend", function () {
      if (dragged) dragged.classList.remove("dragging");
      dragged = null;
    });
    list.addEventListener("dragover", function (ev) {
      if (!dragged) return;
      ev.preventDefault();
      const over = ev.target.closest("[data-item]");
      if (!over || over === dragged) return;
      const box = over.getBoundingClientRect();
      const after = ev.clientY > box.top + box.height / 2;
      list.insertBefore(dragged, after ? over.nextElementSibling : over);
    });
    list.addEventListener("drop", (ev) => ev.preventDefault());
    list.addEventListener("keydown", function (ev) {
      const li = ev.target.closest("[data-item]");
      if (!li || ev.target !== li || !ev.altKey) return;
      if (ev.key === "ArrowUp") {
        ev.preventDefault();
        moveItem(li, -1);
      } else if (ev.key === "ArrowDown") {
        ev.preventDefault();
        moveItem(li, 1);
      }
    });
    list.addEventListener("click", function (ev) {
      const b = ev.target.closest("[data-move]");
      if (!b) return;
      moveItem(b.closest("[data-item]"), Number(b.dataset.move));
      b.focus();
    });
  }

  // ------------------------------------------------------------------ wiring
  function setup(section) {
    const id = section.dataset.exercise;
    const form = section.querySelector("[data-answer]");
    form.addEventListener("submit", function (ev) {
      ev.preventDefault();
      submit(section, answerText(section));
    });
    section.querySelectorAll("[data-choice]").forEach(function (b) {
      b.addEventListener("click", function () {
        section.querySelectorAll("[data-choice]").forEach((o) => o.classList.remove("chosen"));
        b.classList.add("chosen");
        submit(section, b.dataset.choice);
      });
    });
    section.querySelectorAll("[data-toggle]").forEach(function (b) {
      b.addEventListener("click", function () {
        b.setAttribute("aria-pressed", b.getAttribute("aria-pressed") === "true" ? "false" : "true");
      });
    });
    section.querySelectorAll("[data-line]").forEach(function (b) {
      b.addEventListener("click", function () {
        section.querySelectorAll("[data-line]").forEach((o) => o.classList.remove("chosen"));
        b.classList.add("chosen");
        submit(section, b.dataset.line);
      });
    });
    const order = section.querySelector("[data-order]");
    if (order) setupOrder(order);
    const exprInput = section.querySelector("[data-expression]");
    if (exprInput) {
      const box = section.querySelector("[data-preview]");
      exprInput.addEventListener("input", () => preview(exprInput, box));
    }
    const area = section.querySelector("[data-code]");
    if (area && window.SlamEditor) {
      // CodeMirror 6 (vendored): it keeps the textarea's value in sync, which is what is sent
      const pre = section.querySelector("[data-gutter]");
      pre.hidden = true;
      const nonce = document.querySelector('meta[name="slamcourse-style-nonce"]');
      const label = area.getAttribute("aria-label");
      const view = window.SlamEditor.fromTextArea(area, label, nonce && nonce.content);
      editors.set(area, view);
      view.setTabFocusMode(true); // Tab leaves the editor until Ctrl+M (see TAB_LEAVES)
      const help = section.querySelector("[data-editor-help]");
      if (help && help.id) view.contentDOM.setAttribute("aria-describedby", help.id);
      // before CodeMirror's own Ctrl-M binding, so the help line always matches the mode
      view.dom.addEventListener("keydown", function (ev) {
        if (!isTabModeKey(ev)) return;
        ev.preventDefault();
        ev.stopPropagation();
        const indents = !area.dataset.tabIndents;
        view.setTabFocusMode(!indents);
        setTabIndents(section, area, indents);
      }, true);
    } else if (area) {
      const pre = section.querySelector("[data-gutter]");
      gutter(area, pre);
      area.addEventListener("input", () => gutter(area, pre));
      area.addEventListener("keydown", (ev) => editorKeys(section, area, ev));
      area.addEventListener("scroll", () => (pre.scrollTop = area.scrollTop));
    }
    section.querySelector("[data-hint]").addEventListener("click", async function () {
      const h = await post(api("hint", id), {});
      if (h.error) return showResult(section, h);
      section.querySelector("[data-hint-count]").textContent = "(" + h.number + "/" + h.total + ")";
      if (h.hint_html) {
        const li = document.createElement("li");
        setHTML(li, h.hint_html);
        section.querySelector("[data-hints]").appendChild(li);
        li.setAttribute("tabindex", "-1");
        li.focus();
      } else {
        announce(section, "No more hints for this exercise.");
      }
    });
    const giveup = section.querySelector("[data-giveup]");
    giveup.addEventListener("click", async function () {
      if (!giveup.dataset.confirm) {
        giveup.dataset.confirm = "1";
        giveup.textContent = "Really give up? Click again";
        return;
      }
      delete giveup.dataset.confirm;
      giveup.textContent = "Give up and see the explanation";
      const r = await post(api("giveup", id), {});
      if (r.error) return showResult(section, r);
      showExplanation(section, r.explanation_html);
      showPlot(section, r.plot_svg);
      setStatus(section, r.exercise_status);
      refreshSidebar(r.summary);
    });
    const practice = section.querySelector("[data-practice]");
    if (practice) {
      practice.addEventListener("change", async function () {
        const data = await get(api("exercise", id) + (practice.checked ? "?canonical=1" : ""));
        setHTML(section.querySelector("[data-prompt]"), data.text_html);
        showPlot(section, data.plot_svg);
        section.classList.toggle("practising", practice.checked);
        announce(section, practice.checked
          ? "Showing the lesson's own numbers: answers are graded but not counted."
          : "Showing your own numbers again.");
      });
    }
  }

  document.addEventListener("DOMContentLoaded", function () {
    typeset(document.body);
    document.querySelectorAll("section.exercise").forEach(setup);
    document.documentElement.dataset.ready = "1";
  });

  window.slamcourse = { toLatex: toLatex };
})();
