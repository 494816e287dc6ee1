"""The lesson (docs/teaching.md) quotes what the model computes, and its links open
states the explorer understands."""
import re
from pathlib import Path
from urllib.parse import parse_qs, urlsplit

import pytest

from app.lesson import REGIME_TEXTS, STEPS, fact_line, lesson_url
from app.urlstate import parse
from model import REGIMES

DOC = (Path(__file__).resolve().parents[1] / "docs" / "teaching.md").read_text(encoding="utf-8")


@pytest.mark.parametrize("step", STEPS, ids=lambda s: s.key)
def test_the_document_quotes_the_model(step):
    assert f"> Model check: {fact_line(step)}" in DOC
    assert f"]({lesson_url(step)})" in DOC


def test_every_link_is_a_lesson_state_the_page_reads():
    links = re.findall(r"\]\((http://localhost:5006/app\?[^)]*)\)", DOC)
    assert sorted(links) == sorted(lesson_url(s) for s in STEPS)
    for link in links:
        query = parse_qs(urlsplit(link).query)
        values, notices = parse(query)
        assert notices == [], (link, notices)
        step = next(s for s in STEPS if lesson_url(s) == link)
        assert values["k_r"] == REGIMES[step.regime].k_r
        assert values["theta0"] == step.theta0_deg


def test_lesson_lasts_45_minutes_and_covers_the_regimes():
    assert sum(s.minutes for s in STEPS) + 5 == 45  # plus the 5-minute introduction
    assert {s.regime for s in STEPS} == set(REGIMES) == set(REGIME_TEXTS)
