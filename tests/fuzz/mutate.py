"""
Mutations of a fuzz input, each drawn from a ``random.Random`` and noted in ``tree.notes``:

- ``structure``: XML elements deleted, duplicated, swapped, nested in another, renamed; attributes
  deleted; or the text truncated, lines deleted, duplicated or swapped, garbage inserted, a DOCTYPE
  with entities (a billion laughs, an external entity);
- ``numbers``: numeric attribute values replaced by NaN, ±inf, 1e308, -0, subnormals, 1e-300,
  huge exponents, hex, blanks;
- ``names``: a link or joint name (and every reference to it) replaced by a hostile one: a
  newline or CR followed by a canary (:data:`CANARY`), U+2028, ``__proto__``, 100 000 characters,
  bidirectional overrides, markup;
- ``encoding``: UTF-16 with or without BOM, UTF-8 BOM, CR-only or mixed line endings, bare CRs,
  invalid bytes, odd declared encodings;
- ``xacro``: huge strings, deep macro recursion, YAML anchor bombs, ``$(env)``, includes of
  itself or of a device, Python escapes in expressions;
- ``layout`` (fuzz.layouts): links in and out, loops, FIFOs, links to /dev/zero, unreadable and
  huge files, planted output links, control characters in file names.
"""

from __future__ import annotations

import random
import re
from pathlib import PurePosixPath

from lxml import etree

from fuzz import layouts
from fuzz.tree import Tree, file

#: what a hostile name puts after a line break: an output line starting with it was injected
CANARY = "FUZZINJ"

ROBOT_SUFFIXES = (".urdf", ".xacro", ".xml")


def robot_files(tree: Tree) -> list[str]:
    """The robot texts of ``tree`` (paths relative to work/), the main one first."""
    found = [p for p in tree.work_files() if PurePosixPath(p).suffix.lower() in ROBOT_SUFFIXES]
    if tree.main in found:
        found.remove(tree.main)
        found.insert(0, tree.main)
    return found


def shown(path: str) -> str:
    """A path short enough for a note."""
    return path if len(path) <= 60 else "…" + path[-50:]


def _target(rng: random.Random, tree: Tree) -> str | None:
    files = robot_files(tree)
    if not files:
        return None
    return files[0] if rng.random() < 0.75 else rng.choice(files)


def _text(tree: Tree, path: str) -> str | None:
    node = tree.get(path)
    try:
        return node.data.decode("utf-8") if node is not None and node.kind == "file" else None
    except UnicodeDecodeError:
        return None


# --- structure ---------------------------------------------------------------------------------

#: a billion laughs: entity g is 10**7 characters
_LAUGHS = '<!ENTITY a "aaaaaaaaaa">' + "".join(
    f'<!ENTITY {chr(98 + i)} "{("&" + chr(97 + i) + ";") * 10}">' for i in range(6)
)

_PARSER = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False, huge_tree=False)


def structure(rng: random.Random, tree: Tree) -> str | None:
    path = _target(rng, tree)
    text = _text(tree, path) if path else None
    if text is None:
        return None
    op = rng.choice(["element", "element", "element", "truncate", "lines", "garbage", "doctype"])
    if op == "element":
        changed = _element_op(rng, text)
        if changed is None:
            op = "lines"
        else:
            tree.put(path, changed[1])
            return f"structure {changed[0]} {shown(path)}"
    if op == "truncate":
        cut = rng.randrange(len(text) + 1)
        tree.put(path, text[:cut])
        return f"truncate {shown(path)} at {cut}"
    if op == "lines":
        lines = text.splitlines(keepends=True)
        if len(lines) < 2:
            return None
        i, j = sorted(rng.sample(range(len(lines)), 2))
        how = rng.choice(["delete", "duplicate", "swap"])
        if how == "delete":
            del lines[i:j]
        elif how == "duplicate":
            lines[i:i] = lines[i : j + 1]
        else:
            lines[i], lines[j] = lines[j], lines[i]
        tree.put(path, "".join(lines))
        return f"lines {how} {shown(path)}"
    if op == "garbage":
        at = rng.randrange(len(text) + 1)
        junk = rng.choice(
            [
                "<",
                ">",
                "&",
                "&bogus;",
                "<![CDATA[x]]>",
                "<?pi x?>",
                "</link>",
                "<link>",
                '"',
                "\x00",
                "\ufffe",
                "]]>",
                "<!-- -- -->",
            ]
        )
        tree.put(path, text[:at] + junk + text[at:])
        return f"garbage {junk!r} {shown(path)}"
    # a DOCTYPE: entity expansion (billion laughs) or an external entity must not be honoured
    doctype = rng.choice(
        [
            "<!DOCTYPE robot [" + _LAUGHS + "]>",
            '<!DOCTYPE robot [<!ENTITY x SYSTEM "file:///etc/hostname">]>',
            '<!DOCTYPE robot [<!ENTITY x SYSTEM "../outside/deploy.sh">]>',
            '<!DOCTYPE robot SYSTEM "http://127.0.0.1:9/robot.dtd">',
        ]
    )
    entity = "&g;" if "ENTITY g" in doctype else "&x;" if "ENTITY x" in doctype else ""
    body = re.sub(r"<\?xml[^>]*\?>\s*", "", text, count=1)
    body = re.sub(r'(<robot\b[^>]*\bname=")', r"\1" + entity, body, count=1)
    tree.put(path, doctype + "\n" + body)
    return f"doctype {shown(path)}"


def _element_op(rng: random.Random, text: str) -> tuple[str, str] | None:
    match = re.search(r"<\?xml[^>]*\?>", text)
    prolog = match.group(0) + "\n" if match and match.start() == 0 else ""
    try:
        root = etree.fromstring(text.encode("utf-8"), _PARSER)
    except (etree.XMLSyntaxError, ValueError):
        return None
    elements = [e for e in root.iter() if isinstance(e.tag, str) and e is not root]
    if not elements:
        return None
    element = rng.choice(elements)
    parent = element.getparent()
    op = rng.choice(
        ["delete", "duplicate", "swap", "nest", "rename", "attribute", "attribute", "move-out"]
    )
    if op == "delete":
        parent.remove(element)
    elif op == "duplicate":
        element.addnext(etree.fromstring(etree.tostring(element)))
    elif op == "swap":
        other = rng.choice(elements)
        if other is element or element in other.iterancestors() or other in element.iterancestors():
            return None
        a, b = etree.Element("a"), etree.Element("b")
        element.addprevious(a)
        other.addprevious(b)
        a.addprevious(other)
        b.addprevious(element)
        a.getparent().remove(a)
        b.getparent().remove(b)
    elif op == "nest":
        host = rng.choice(elements)
        if host is element or host in element.iter():
            return None
        host.append(element)
    elif op == "rename":
        element.tag = rng.choice(
            [
                "link",
                "joint",
                "inertial",
                "inertia",
                "mass",
                "origin",
                "geometry",
                "box",
                "mesh",
                "visual",
                "collision",
                "robot",
                "x",
            ]
        )
    elif op == "attribute":
        if not element.attrib:
            return None
        del element.attrib[rng.choice(list(element.attrib))]
    else:  # to the root
        root.append(element)
    return op, prolog + etree.tostring(root, encoding="unicode") + "\n"


# --- numbers -----------------------------------------------------------------------------------

SPECIALS = (
    "nan", "NaN", "-nan", "inf", "-inf", "Infinity", "1e308", "-1e308", "1.7976931348623157e308",
    "-0", "-0.0", "5e-324", "-5e-324", "2.2250738585072014e-308", "1e-300", "1e-320", "1e999",
    "1e-999", "1e99999999999", "0x10", "0x1p-3", "", " ", "  ", "1 2", "1,5", "+.5e+2", "1_000",
    "١٢", "1e", ".", "-", "0e0", "00001", "1" * 400, "0." + "0" * 400 + "1", "9" * 30 + "e-30",
)  # fmt: skip
_NUMBER = re.compile(r'(?<=[" ])-?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?=[" ])')


def numbers(rng: random.Random, tree: Tree) -> str | None:
    path = _target(rng, tree)
    text = _text(tree, path) if path else None
    if not text:
        return None
    spots = list(_NUMBER.finditer(text))
    if not spots:
        return None
    chosen = sorted(
        rng.sample(spots, k=min(len(spots), rng.choice([1, 1, 2, 3, 8]))), key=lambda m: m.start()
    )
    out, last, used = [], 0, []
    for match in chosen:
        value = rng.choice(SPECIALS)
        out += [text[last : match.start()], value]
        last = match.end()
        used.append(value)
    tree.put(path, "".join(out) + text[last:])
    return f"numbers {used!r} {shown(path)}"


# --- names -------------------------------------------------------------------------------------

HOSTILE_NAMES = (
    f"a&#10;{CANARY}::error file=x,line=1::injected",
    f"a&#13;{CANARY}",
    f"a&#13;&#10;{CANARY}",
    f"&#x2028;{CANARY}",
    f"&#x2029;{CANARY}",
    f"&#x85;{CANARY}",
    f"&#9;{CANARY}",
    "__proto__", "constructor", "toString", "hasOwnProperty", "valueOf", "prototype",
    "L" * 100_000,
    "rücken_链接_🤖", "&#x202e;evil", "a&#x200b;b", "&#xfeff;bom",
    "&lt;script&gt;alert(1)&lt;/script&gt;", "&lt;/script&gt;&lt;img src=x onerror=alert(1)&gt;",
    "%s%n{0}", "${x}", "$(env HOME)", "..", "/", "", " ", "a b", "&amp;&quot;&apos;",
    "&#27;[31mred", "\x1b[31mred", "a\x07bell",  # invalid XML 1.0: the parse error's message
)  # fmt: skip


def names(rng: random.Random, tree: Tree) -> str | None:
    path = _target(rng, tree)
    text = _text(tree, path) if path else None
    if not text:
        return None
    found = sorted(set(re.findall(r'<(?:link|joint)\s+name="([^"$]+)"', text)))
    if not found:
        return None
    old = rng.choice(found)
    new = rng.choice(HOSTILE_NAMES)
    if rng.random() < 0.8:  # every reference too, so the tree stays connected
        text = text.replace(f'"{old}"', f'"{new}"')
    else:
        text = text.replace(f'name="{old}"', f'name="{new}"', 1)
    tree.put(path, text)
    return f"names {old!r} -> {new[:40]!r} {shown(path)}"


# --- encodings ---------------------------------------------------------------------------------

DECLARED = (
    "UTF-16",
    "utf-16le",
    "UTF-32",
    "ISO-8859-1",
    "latin-1",
    "ascii",
    "shift_jis",
    "cp500",
    "EBCDIC-US",
    "UTF-7",
    "no-such-encoding",
    "utf8",
    "",
    "UTF-8 ",
)


def encoding(rng: random.Random, tree: Tree) -> str | None:
    path = _target(rng, tree)
    text = _text(tree, path) if path else None
    if text is None:
        return None
    op = rng.choice(
        [
            "utf16",
            "utf16-bare",
            "utf8-bom",
            "cr",
            "bare-cr",
            "mixed",
            "invalid",
            "declared",
            "declared",
            "utf32",
            "latin1",
        ]
    )
    body = re.sub(r"^\s*<\?xml[^>]*\?>\s*", "", text)
    if op == "utf16":
        codec = rng.choice(["utf-16", "utf-16-le", "utf-16-be"])
        data = f'<?xml version="1.0" encoding="UTF-16"?>\n{body}'.encode(codec)
        if codec != "utf-16" and rng.random() < 0.5:
            data = ("\ufeff" + f'<?xml version="1.0" encoding="UTF-16"?>\n{body}').encode(codec)
    elif op == "utf16-bare":
        data = body.encode(rng.choice(["utf-16", "utf-16-le"]))
    elif op == "utf32":
        data = f'<?xml version="1.0" encoding="UTF-32"?>\n{body}'.encode("utf-32")
    elif op == "utf8-bom":
        data = b"\xef\xbb\xbf" + text.encode("utf-8")
    elif op == "cr":
        data = text.replace("\r\n", "\n").replace("\n", "\r").encode("utf-8")
    elif op == "bare-cr":
        spots = [m.end() for m in re.finditer(r">|\s", text)] or [0]
        chars = list(text)
        for at in sorted(
            rng.sample(spots, k=min(len(spots), rng.choice([1, 3, 10]))), reverse=True
        ):
            chars.insert(at, "\r")
        data = "".join(chars).encode("utf-8")
    elif op == "mixed":
        lines = text.split("\n")
        data = "".join(line + rng.choice(["\n", "\r\n", "\r", "\n\r"]) for line in lines).encode(
            "utf-8"
        )
    elif op == "invalid":
        raw = bytearray(text.encode("utf-8"))
        for _ in range(rng.choice([1, 2, 5])):
            raw[rng.randrange(len(raw) + 1) : 0] = rng.choice(
                [
                    b"\xff",
                    b"\xfe",
                    b"\xc0\x80",
                    b"\xed\xa0\x80",
                    b"\x80",
                    b"\xf4\x90\x80\x80",
                    b"\x00",
                ]
            )
        data = bytes(raw)
    elif op == "latin1":
        data = (
            f'<?xml version="1.0" encoding="ISO-8859-1"?>\n<!-- bras articulé -->\n{body}'.encode(
                "latin-1", errors="replace"
            )
        )
    else:
        declared = rng.choice(DECLARED)
        head = f'<?xml version="1.0" encoding="{declared}"?>\n'
        data = f"{head}<!-- é ü ロボット -->\n{body}".encode()
    tree.nodes[tree.key(path)] = file(data)
    return f"encoding {op} {shown(path)}"


# --- hostile xacro -----------------------------------------------------------------------------

XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
_BOMB = "a: &a [x, x, x, x, x, x, x, x, x, x]\n" + "".join(
    f"{chr(98 + i)}: &{chr(98 + i)} [{', '.join([f'*{chr(97 + i)}'] * 10)}]\n" for i in range(8)
)

HOSTILE_XACRO = {
    "huge-name": "<link name=\"${'x'*10**8}\"/>",
    "huge-mass": '<link name="h"><inertial><mass value="${\'1\'*10**7}"/></inertial></link>',
    "huge-attribute": '<link name="h"><visual><geometry><mesh filename="${\'a/\'*10**6}"/>'
    "</geometry></visual></link>",
    "many-links": '<xacro:macro name="m" params="n"><link name="l${n}"/>'
    '<xacro:if value="${n > 0}"><xacro:m n="${n-1}"/></xacro:if></xacro:macro><xacro:m n="900"/>',
    "recursion": '<xacro:macro name="r" params="n"><xacro:r n="${n+1}"/></xacro:macro>'
    '<xacro:r n="0"/>',
    "power": '<link name="${10**10**10}"/>',
    "import": "<link name=\"${__import__('os').system('touch pwned')}\"/>",
    "open": "<link name=\"${open('/etc/hostname').read()}\"/>",
    "dunder": '<link name="${().__class__.__base__.__subclasses__()}"/>',
    "env": '<link name="$(env HOME)"/><link name="$(env FUZZ_NO_SUCH_VARIABLE)"/>',
    "optenv": '<link name="$(optenv FUZZ_SECRET_TOKEN fallback)"/>',
    "eval": '<link name="$(eval 1+1)"/>',
    "undefined-arg": '<link name="$(arg no_such_arg)"/>',
    "bad-find": '<xacro:include filename="$(find no_such_package)/x.xacro"/>',
    "self-include": '<xacro:include filename="SELF"/>',
    "include-device": '<xacro:include filename="/dev/zero"/>',
    "include-folder": '<xacro:include filename="."/>',
    "include-glob": '<xacro:include filename="*.xacro"/>',
    "yaml-bomb": '<xacro:property name="y" value="${xacro.load_yaml(\'bomb.yaml\')}"/>'
    '<link name="${str(y)}"/>',
    "yaml-device": '<xacro:property name="y" value="${xacro.load_yaml(\'/dev/zero\')}"/>',
    "yaml-missing": '<xacro:property name="y" value="${xacro.load_yaml(\'nope.yaml\')}"/>',
    "yaml-tag": '<xacro:property name="y" value="${xacro.load_yaml(\'tag.yaml\')}"/>'
    '<link name="${y}"/>',
    "deep-expression": '<link name="${' + "(" * 400 + "1" + ")" * 400 + '}"/>',
    "unknown-macro": "<xacro:no_such_macro/>",
    "property-loop": '<xacro:property name="p" value="${q}"/>'
    '<xacro:property name="q" value="${p}"/><link name="${p}"/>',
    "lazy-block": '<xacro:property name="blk"><link name="b"/></xacro:property>'
    '<xacro:insert_block name="blk"/><xacro:insert_block name="blk"/>',
}


def xacro(rng: random.Random, tree: Tree) -> str | None:
    """A hostile xacro construct inserted into a robot file (made a xacro file if need be)."""
    path = _target(rng, tree)
    text = _text(tree, path) if path else None
    if text is None:
        return None
    name = rng.choice(sorted(HOSTILE_XACRO))
    snippet = HOSTILE_XACRO[name].replace("SELF", PurePosixPath(path).name)
    folder = str(PurePosixPath(path).parent)
    if name == "yaml-bomb":
        tree.put(f"{folder}/bomb.yaml", _BOMB)
    if name == "yaml-tag":
        tree.put(f"{folder}/tag.yaml", "!!python/object/apply:os.system ['touch pwned']\n")
    if "xmlns:xacro" not in text:
        text = re.sub(r"<robot\b", f"<robot {XACRO_NS}", text, count=1)
    match = re.search(r"<robot\b[^>]*>", text)
    if match is None:
        return None
    text = text[: match.end()] + "\n  " + snippet + text[match.end() :]
    if not path.endswith(".xacro"):
        tree.nodes.pop(tree.key(path))
        path = path.rsplit(".", 1)[0] + ".urdf.xacro"
        if tree.main != ".":
            tree.main = path
    tree.put(path, text)
    return f"xacro {name} {shown(path)}"


MUTATIONS = {
    "structure": (structure, 30),
    "numbers": (numbers, 20),
    "names": (names, 15),
    "encoding": (encoding, 15),
    "xacro": (xacro, 8),
    "layout": (layouts.layout, 12),
}


def mutate(rng: random.Random, tree: Tree, count: int) -> Tree:
    """``tree`` after ``count`` mutations (those that do not apply are skipped)."""
    kinds = list(MUTATIONS)
    weights = [MUTATIONS[k][1] for k in kinds]
    # encodings last: the other mutations edit texts
    chosen = sorted(rng.choices(kinds, weights=weights, k=count), key=lambda k: k == "encoding")
    for kind in chosen:
        note = MUTATIONS[kind][0](rng, tree)
        if note:
            tree.notes.append(note)
    return tree
