"""The page's "This view as Python" card (app/views/code.py) follows the controls, and its
snippet runs and prints the fixed array's number the page shows."""
import subprocess
import sys

from app.state import ExplorerState


def test_the_card_follows_the_controls_and_runs():
    from app.views.code import CodeView
    from app.results import SessionResults

    state = ExplorerState()
    view = CodeView(state=state, results=SessionResults(state))
    # folded, the card writes nothing (a slider move costs no rendering) ...
    assert view.card.collapsed and view.code.object == ""
    state.param.update(k_r=0.5, F_N=2.0)
    assert view.code.object == ""
    # ... opened, it shows the snippet of the controls as they are now, and follows them
    view.card.collapsed = False
    assert "k_r=0.5" in view.code.object and "F_N=2.0" in view.code.object
    state.param.update(k_r=0.25)
    text = view.code.object
    assert "k_r=0.25" in text and "k_r=0.5" not in text
    state.k_r = 0.5
    text = view.code.object
    assert text.startswith("```python") and "k_r=0.5" in text and "F_N=2.0" in text
    code = text.removeprefix("```python\n").removesuffix("```")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert "F_T,x" in out.stdout or "FTx" in out.stdout, out.stdout[:500]
    assert "micropillar-friction" in view.version.object
