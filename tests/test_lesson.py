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


def test_the_links_keep_the_presentation_and_wait_for_the_prediction():
    """A lesson is taught from one screen: every link opens in projector mode and none
    starts the animation before the class has predicted (``--screen``: no projector)."""
    for step in STEPS:
        values, _ = parse(parse_qs(urlsplit(lesson_url(step)).query))
        assert values.get("projector") is True and not values.get("play"), lesson_url(step)
        values, _ = parse(parse_qs(urlsplit(lesson_url(step, projector=False)).query))
        assert not values.get("projector") and not values.get("play")


def test_lesson_lasts_45_minutes_and_covers_the_regimes():
    assert sum(s.minutes for s in STEPS) + 5 == 45  # plus the 5-minute introduction
    assert {s.regime for s in STEPS} == set(REGIMES) == set(REGIME_TEXTS)
