"""
Whitespace-separated plain decimals read fast, bit for bit as ``np.fromstring(text,
dtype=np.float64, sep=" ")`` reads them, and short decimal integers: the OBJ reader's coordinates
(:mod:`.obj_soup`), the counts of its ``vt`` and ``vn`` lines (read only to fail where trimesh
fails) and its face indices; the COLLADA reader's ``<float_array>`` (:mod:`.collada`, which
rounds them to float32 as pycollada does) and ``<p>`` indices.

numpy's float parser takes ~190 ns a number; its integer parser ~25 ns. A plain decimal
(``[+-]digits[.digits]``, ``[+-]digits.``, ``[+-].digits``) of at most 15 digits is its digits
as an integer ``m`` (below 2**53: exact in float64) over ``10**k`` (``k`` <= 15: exact): IEEE
division rounds ``m / 10**k`` correctly, as ``strtod`` rounds the decimal. So the digits are read
as integers, and each token's point and sign are found with numpy. Anything else (an exponent,
``nan``, a comma, a 16th digit) is declined (``None``): the caller reads it its own way.
Integers of up to 8 digits are read eight bytes at a time (:func:`small_integers`).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

#: the bytes of plain decimal numbers and their separators (str.split's and numpy's whitespace
#: but \x1c-\x1f, which split one and not the other)
PLAIN = b"0123456789.+- \t\n\r\x0b\x0c"
#: the most digits read exactly as an integer (below 2**53) and scaled by one division
EXACT_DIGITS = 15
_BLANK, _POINT, _MINUS, _PLUS = ord(" "), ord("."), ord("-"), ord("+")


def plain_decimals(
    text: bytes, values: bool = True, exponents: bool = False
) -> NDArray[np.float64] | int | None:
    """
    The numbers of ``text`` as ``np.fromstring(text, dtype=np.float64, sep=" ")`` reads them,
    when every whitespace-separated token is a plain decimal of at most 15 digits; ``None``
    otherwise. ``values=False``: only their count when every token is a plain decimal (of any
    number of digits: ``np.fromstring`` reads them all), or ``None``. ``exponents``: a token may
    also end in an exponent (``e`` or ``E``, an optional sign, 1 to 4 digits), read when the
    value is exact (``m * 10**e`` or ``m / 10**-e`` with ``|e| <= 22``), declined otherwise.
    """
    if not text:
        return None
    odd = text.translate(None, PLAIN)
    if odd and not (exponents and values and not odd.translate(None, b"eE")):
        return None
    body = np.frombuffer(text, dtype=np.uint8)
    starts, ends = _tokens(body)
    count = len(starts)
    if not count:
        return None
    # an exponent: at most one a token, after its first byte; the mantissa ends there
    marks = np.flatnonzero((body | 32) == ord("e")) if odd else np.zeros(0, np.intp)
    stops = ends
    if len(marks):
        token = _owners(marks, starts, ends)
        if token is None or (marks <= starts[token]).any():
            return None
        stops = ends.copy()
        stops[token] = marks
        after = body[np.minimum(marks + 1, len(body) - 1)]
        exp_signed = (after == _MINUS) | (after == _PLUS)
        exp_digits = ends[token] - marks - 1 - exp_signed
        if exp_digits.min() < 1 or exp_digits.max() > 4:
            return None
        exp_signs = int(np.count_nonzero(exp_signed))
    else:
        exp_signs = 0
    # a sign: a token's first byte, or the one after its exponent's mark
    first = body[starts]
    negative = first == _MINUS
    signed = negative | (first == _PLUS)
    signs = int(np.count_nonzero(signed))
    if signs + exp_signs != text.count(b"-") + text.count(b"+"):
        return None
    # a point: at most one a token, in its mantissa
    points = np.flatnonzero(body == _POINT)
    owner = _owners(points, starts, stops)
    if owner is None:
        return None
    digits = stops - starts
    if signs:
        digits -= signed
    digits[owner] -= 1
    if digits.min() < 1:  # "-", ".", "-."
        return None
    if not values:
        return count
    if digits.max() > EXACT_DIGITS:
        return None
    if len(marks):
        read = np.fromstring(text.translate(_EXPONENT_TABLE, b".+"), dtype=np.int64, sep=" ")
        if len(read) != count + len(marks):  # pragma: no cover - every part has a digit
            return None
        has_exp = np.zeros(count, dtype=bool)
        has_exp[token] = True
        index = np.arange(count)
        index += np.cumsum(has_exp) - has_exp
        numbers = np.abs(read[index]).astype(np.float64)
        exponent = np.zeros(count, dtype=np.intp)
        exponent[token] = read[index[token] + 1]
    else:
        mantissas = np.fromstring(text.translate(None, b".+-"), dtype=np.int64, sep=" ")
        if len(mantissas) != count:  # pragma: no cover - every token has a digit
            return None
        numbers = mantissas.astype(np.float64)
        del mantissas
        exponent = np.zeros(count, dtype=np.intp)
    exponent[owner] -= stops[owner] - points - 1
    if len(marks):
        if np.abs(exponent).max() > 22:
            return None
        numbers /= _POW10[np.maximum(-exponent, 0)]
        numbers *= _POW10[np.maximum(exponent, 0)]
    else:
        numbers /= _POW10[np.negative(exponent, out=exponent)]
    if signs:
        np.negative(numbers, out=numbers, where=negative)
    return numbers


_EXPONENT_TABLE = bytes.maketrans(b"eE", b"  ")
_POW10 = 10.0 ** np.arange(23)


def _tokens(body: NDArray[np.uint8]) -> tuple[NDArray[np.intp], NDArray[np.intp]]:
    """Each whitespace-separated token's start and end (the text's control characters all
    whitespace)."""
    blanks = np.flatnonzero(body <= _BLANK)
    bounds = np.empty(len(blanks) + 2, dtype=np.intp)
    bounds[0], bounds[-1] = -1, len(body)
    bounds[1:-1] = blanks
    del blanks
    kept = np.diff(bounds) > 1
    starts = bounds[:-1][kept]
    starts += 1
    return starts, bounds[1:][kept]


def _owners(at: NDArray[np.intp], starts, ends) -> NDArray[np.intp] | None:
    """The token of each position ``at`` (ascending, each in a token), or ``None`` when two are
    in one token or one lies at or past ``ends`` (where its token's part ends)."""
    if len(at) == len(starts) and (at >= starts).all() and (at < ends).all():
        return np.arange(len(at))  # one in every token, as exporters write them
    owner = np.searchsorted(starts, at, side="right") - 1
    if len(at) > 1 and not (np.diff(owner) > 0).all():
        return None
    if (at >= ends[owner]).any():
        return None
    return owner


_ZEROS = np.uint64(0x3030303030303030)
_ONES = np.uint64(0xFFFFFFFFFFFFFFFF)
_PAIRS = np.uint64(0x000000FF000000FF)
_MUL1 = np.uint64(100 + (1000000 << 32))
_MUL2 = np.uint64(1 + (10000 << 32))


def small_integers(body, starts, stops) -> NDArray[np.int64] | None:
    """
    The decimal integers ``body[starts:stops]`` (digits only, 1 to 8 of them; ``None`` when
    one is longer): each the 8 bytes ending at ``stop``, read as one unsigned integer, the
    bytes before ``start`` masked, its digits summed in three multiplications (SWAR, as
    ``fast_float`` and ``simdjson`` read eight digits).
    """
    digits = stops - starts
    if not len(digits):
        return np.zeros(0, np.int64)
    if digits.max() > 8 or len(body) < 8:
        return None
    words = np.ndarray((len(body) - 7,), dtype="<u8", buffer=body, strides=(1,))
    first = stops - 8
    early = np.flatnonzero(first < 0)  # within 8 bytes of the text's start
    if len(early):
        first[early] = 0
    value = words[first]
    del first
    np.subtract(8, digits, out=digits)
    digits <<= 3
    mask = np.left_shift(_ONES, digits.view(np.uint64))  # the number's bytes
    del digits
    value &= mask
    mask &= _ZEROS
    value -= mask  # each byte its digit, those before the number 0
    np.right_shift(value, np.uint64(8), out=mask)
    value *= np.uint64(10)
    value += mask  # each byte ten times its digit and the next one's
    np.right_shift(value, np.uint64(16), out=mask)
    mask &= _PAIRS
    mask *= _MUL2
    value &= _PAIRS
    value *= _MUL1
    value += mask
    value >>= np.uint64(32)
    result = value.view(np.int64)
    for at in early.tolist():
        result[at] = int(body[starts[at] : stops[at]].tobytes())
    return result
