"""decimal_text: plain decimals and short integers read fast, as numpy reads them."""

from __future__ import annotations

import re

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from inertia_kit.physics.decimal_text import plain_decimals, small_integers


@st.composite
def decimal_texts(draw):
    digits = st.text("0123456789", min_size=0, max_size=9)
    numbers = []
    for _ in range(draw(st.integers(1, 12))):
        sign = draw(st.sampled_from(["", "", "-", "+"]))
        whole, fraction = draw(digits), draw(digits)
        dot = draw(st.sampled_from([".", ".", ""]))
        numbers.append(sign + whole + dot + fraction if (whole or fraction) else sign + "0")
    separators = st.sampled_from([" ", "  ", "\t", "\n", " \r\n"])
    return (" " + "".join(n + draw(separators) for n in numbers) + "\n").encode()


@settings(max_examples=500, deadline=None)
@given(decimal_texts())
def test_plain_decimals_read_as_numpy_reads_them(text):
    """The fast path for coordinates gives np.fromstring's numbers, bit for bit, or declines."""
    fast = plain_decimals(text)
    if fast is not None:
        exact = np.fromstring(text, dtype=np.float64, sep=" ")
        assert fast.tobytes() == exact.tobytes(), (text, fast, exact)


def test_decimals_decline_what_they_do_not_read():
    for text in (
        b" 1e5\n",
        b" nan\n",
        b" 1.2.3\n",
        b" 1-2\n",
        b" -\n",
        b" .\n",
        b" 1234567890.1234567\n",
    ):
        assert plain_decimals(text) is None, text


@st.composite
def decimal_tokens(draw):
    """Tokens of digits, points, signs and exponents: plain decimals, most of them."""
    pieces = st.sampled_from(["0", "1", "7", "12", "007", "123456789", "-", "+", ".", "e", "E"])
    tokens = [
        "".join(draw(st.lists(pieces, min_size=1, max_size=6)))
        for _ in range(draw(st.integers(1, 8)))
    ]
    separators = st.sampled_from([" ", "  ", "\n", "\t", " \r\n"])
    return (" " + "".join(t + draw(separators) for t in tokens)).encode()


@settings(max_examples=1000, deadline=None)
@given(decimal_tokens(), st.booleans())
def test_decimals_with_exponents_read_as_numpy_reads_them(text, exponents):
    """plain_decimals, exponents allowed or not: np.fromstring's numbers, bit for bit, or
    declined; and its count of plain decimals, when it gives one, numpy's."""
    fast = plain_decimals(text, exponents=exponents)
    if fast is not None:
        exact = np.fromstring(text, dtype=np.float64, sep=" ")
        assert len(exact) == len(text.split())
        assert fast.tobytes() == exact.tobytes(), (text, fast, exact)
    count = plain_decimals(text, values=False)
    if count is not None:
        assert count == len(text.split()) == len(np.fromstring(text, dtype=np.float64, sep=" "))


@settings(max_examples=300, deadline=None)
@given(st.lists(st.integers(0, 99_999_999), min_size=1, max_size=30), st.integers(0, 3))
def test_small_integers_read_each_number(numbers, lead):
    text = " " * lead + " ".join(map(str, numbers)) + "\n"
    body = np.frombuffer(text.encode(), dtype=np.uint8).copy()
    spans = [(m.start(), m.end()) for m in re.finditer(r"\d+", text)]
    starts = np.array([a for a, _ in spans])
    stops = np.array([b for _, b in spans])
    found = small_integers(body, starts, stops)
    if len(body) >= 8:
        assert found is not None
        assert found.tolist() == numbers
