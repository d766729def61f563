// slamcourse's code editor: CodeMirror 6 with Python highlighting, bundled by esbuild.
import { EditorState } from "@codemirror/state";
import { EditorView, keymap, lineNumbers, highlightActiveLine, drawSelection } from "@codemirror/view";
import { defaultKeymap, history, historyKeymap, indentWithTab } from "@codemirror/commands";
import { indentUnit, bracketMatching, syntaxHighlighting, defaultHighlightStyle, indentOnInput } from "@codemirror/language";
import { python } from "@codemirror/lang-python";

window.SlamEditor = {
  // Replace a <textarea> by an editor that keeps the textarea's value in sync. ``nonce``: the
  // page's CSP style nonce, which the editor's injected <style> element must carry.
  fromTextArea(area, label, nonce) {
    const view = new EditorView({
      state: EditorState.create({
        doc: area.value,
        extensions: [
          lineNumbers(), history(), drawSelection(), highlightActiveLine(), indentOnInput(),
          bracketMatching(), syntaxHighlighting(defaultHighlightStyle), python(),
          indentUnit.of("    "), EditorState.tabSize.of(4),
          keymap.of([indentWithTab, ...defaultKeymap, ...historyKeymap]),
          EditorView.contentAttributes.of({ "aria-label": label }),
          EditorView.cspNonce.of(nonce || ""),
          EditorView.updateListener.of((u) => { if (u.docChanged) area.value = u.state.doc.toString(); }),
        ],
      }),
    });
    area.parentNode.insertBefore(view.dom, area);
    area.hidden = true;
    return view;
  },
};
