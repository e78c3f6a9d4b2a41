"""Every public routine's dummy arguments and every public type component in the covered
folders carry a FORD doc comment: `!>` on the line(s) before the declaration (the project's
use) or `!!` after it on the same line (FORD's defaults: fpm.toml's [extra.ford] sets no
docmark; `!<` is not read by FORD there), so the API pages of the site say what each one is.

The Fortran is parsed simply, line by line: a module's public names are those of its
`public` statements and `, public` attributes (the house rule: `private` by default); a
routine counts as public when its name is public, when a public generic interface lists it,
or when a public type binds it. Every Fortran file of src/ and app/ is covered."""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[2]
NOT_COVERED: tuple[str, ...] = ()


def covered_files(root=ROOT):
    files = sorted((root / "src").rglob("*.[fF]90")) + sorted((root / "app").rglob("*.[fF]90"))
    return [p for p in files
            if not p.relative_to(root).as_posix().startswith(NOT_COVERED)]


def _code(line):
    """The line without its comment (quotes respected) and stripped."""
    quote = None
    for i, ch in enumerate(line):
        if quote:
            if ch == quote:
                quote = None
        elif ch in "'\"":
            quote = ch
        elif ch == "!":
            return line[:i].strip()
    return line.strip()


def _statements(lines):
    """[(first line index, last line index, joined code)] with continuations joined."""
    out, i = [], 0
    while i < len(lines):
        first, text = i, _code(lines[i])
        while text.endswith("&") and i + 1 < len(lines):
            i += 1
            nxt = _code(lines[i])
            if not nxt and lines[i].lstrip().startswith("!"):
                continue
            text = text[:-1].rstrip() + " " + nxt.lstrip("&").lstrip()
        out.append((first, i, text))
        i += 1
    return out


def _split_names(text):
    """Entity names of a declaration's right-hand side, `a(3) = 0.0, b, c => null()`."""
    names, depth, cur = [], 0, ""
    for ch in text:
        if ch in "([":
            depth += 1
        elif ch in ")]":
            depth -= 1
        if ch == "," and depth == 0:
            names.append(cur)
            cur = ""
        else:
            cur += ch
    names.append(cur)
    return [m.group(1).lower() for n in names if (m := re.match(r"\s*(\w+)", n))]


def _documented(lines, first, last):
    before = first - 1
    if before >= 0 and re.match(r"\s*!>", lines[before]):
        return True
    return any("!!" in lines[k] for k in range(first, last + 1))


HEADER = re.compile(
    r"^(?:(?:pure|elemental|impure|recursive|module|non_recursive|"
    r"(?:type|class|real|integer|logical|character|complex)\s*(?:\([^)]*\))?)\s+)*"
    r"(subroutine|function)\s+(\w+)\s*(?:\(([^)]*)\))?", re.I)
END_ROUTINE = re.compile(r"^end\s*(subroutine|function)\b", re.I)
DECL = re.compile(r"^(?:type|class|real|integer|logical|character|complex|procedure)\b"
                  r".*?::(.*)$", re.I)


def missing_doc_comments(text, label="<text>"):
    """['label:line name'] of public arguments and public type components without a doc
    comment, in the Fortran source `text`."""
    lines = text.splitlines()
    stmts = _statements(lines)
    public, generic, bound = set(), {}, set()
    default_public = True
    public_types = set()
    # pass 1: the module's public names, generics and type bindings
    in_type, type_name, in_iface, iface_name = False, None, False, None
    for _, _, s in stmts:
        low = s.lower()
        if re.match(r"^private\s*$", low) and not in_type:
            default_public = False
        m = re.match(r"^public\s*(?:::)?\s*(.*)$", low)
        if m and not in_type and m.group(1):
            public.update(n.strip() for n in m.group(1).split(",") if n.strip())
        m = re.match(r"^type\s*(,[^:]*)?::\s*(\w+)", low) or re.match(r"^type\s+(\s*)(\w+)\s*$", low)
        if m and not low.startswith("type("):
            in_type, type_name = True, m.group(2)
            if m.group(1) and "public" in m.group(1):
                public.add(type_name)
            continue
        if in_type:
            if re.match(r"^end\s*type", low):
                in_type = False
            else:
                m = re.match(r"^(?:procedure|generic)\b[^:]*::\s*(.*)$", low)
                if m:
                    for part in m.group(1).split(","):
                        target = part.split("=>")[-1].strip()
                        bound.add((type_name, target))
            continue
        m = re.match(r"^(?:abstract\s+)?interface\s*(\w*)", low)
        if m:
            in_iface, iface_name = True, m.group(1)
            continue
        if in_iface:
            if re.match(r"^end\s*interface", low):
                in_iface = False
            m = re.match(r"^(?:module\s+)?procedure\s*(?:::)?\s*(.*)$", low)
            if m and iface_name:
                for n in m.group(1).split(","):
                    generic.setdefault(iface_name, set()).add(n.strip())
    def is_public(name):
        return name in public or (default_public and name not in _private_names(stmts))
    public_routines = set()
    for g, specifics in generic.items():
        if is_public(g):
            public_routines |= specifics
    for tname, target in bound:
        if is_public(tname):
            public_routines.add(target)
    # pass 2: routines' arguments and types' components
    problems = []
    routine = None   # (name, set of dummy names, public)
    depth = 0
    in_type, type_public, comps_private = False, False, False
    for first, last, s in stmts:
        low = s.lower()
        if not low:
            continue
        m = re.match(r"^type\s*(,[^:]*)?::\s*(\w+)", low) or re.match(r"^type\s+(\s*)(\w+)\s*$", low)
        if m and routine is None and not low.startswith("type("):
            in_type, comps_private = True, False
            type_public = is_public(m.group(2))
            continue
        if in_type:
            if re.match(r"^end\s*type", low) or low == "contains":
                in_type = False if low != "contains" else "bindings"
            elif in_type is True and low == "private":
                comps_private = True
            elif in_type is True and type_public:
                d = DECL.match(s)
                if d and not d.group(0).lower().startswith("procedure"):
                    attrs = s.split("::")[0].lower()
                    private = "private" in attrs or (comps_private and "public" not in attrs)
                    if not private and not _documented(lines, first, last):
                        problems.append(f"{label}:{first + 1} component {', '.join(_split_names(d.group(1)))}")
            if re.match(r"^end\s*type", low):
                in_type = False
            continue
        h = HEADER.match(s)
        if h and not low.startswith("end"):
            if routine is None:
                name = h.group(2).lower()
                args = {a.strip().lower() for a in (h.group(3) or "").split(",") if a.strip()}
                routine = (name, args, is_public(name) or name in public_routines)
                depth = 1
            else:
                depth += 1
            continue
        if END_ROUTINE.match(low) or (routine and low == "end"):
            depth -= 1
            if depth == 0:
                routine = None
            continue
        if routine and depth == 1 and routine[2]:
            d = DECL.match(s)
            if d:
                hit = [n for n in _split_names(d.group(1)) if n in routine[1]]
                if hit and not _documented(lines, first, last):
                    problems.append(f"{label}:{first + 1} {routine[0]}({', '.join(hit)})")
    return problems


def _private_names(stmts):
    names = set()
    for _, _, s in stmts:
        m = re.match(r"^private\s*::\s*(.*)$", s.lower())
        if m:
            names.update(n.strip() for n in m.group(1).split(","))
    return names


def all_missing(root=ROOT):
    out = []
    for path in covered_files(root):
        out += missing_doc_comments(path.read_text(), path.relative_to(root).as_posix())
    return out


def test_every_public_argument_and_component_has_a_doc_comment():
    missing = all_missing()
    assert not missing, f"{len(missing)} without a doc comment:\n" + "\n".join(missing)


GOOD = """\
module davit_made_up
  implicit none
  private
  public :: thing_type, make, twice
  !> A thing.
  type :: thing_type
    !> Its mass [kg].
    real :: m = 0.0
    real :: k = 1.0  !! Its stiffness [N/m].
  end type thing_type
contains
  !> Twice x.
  pure function twice(x, &
                      y) result(r)
    !> A length [m].
    real, intent(in) :: x
    real, intent(in) :: y  !! Another length [m].
    real :: r
    r = 2 * x + y
  end function twice
  subroutine make(t)
    !> The thing made.
    type(thing_type), intent(out) :: t
    t%m = 1.0
  end subroutine make
  subroutine hidden(u)
    real, intent(in) :: u
  end subroutine hidden
end module davit_made_up
"""


def _line(text, needle):
    return next(i + 1 for i, line in enumerate(text.splitlines()) if needle in line)


def test_a_documented_module_passes():
    assert missing_doc_comments(GOOD) == []


def test_an_undocumented_argument_fails():
    bad = GOOD.replace("    !> A length [m].\n", "")
    assert missing_doc_comments(bad) == [f"<text>:{_line(bad, ':: x')} twice(x)"]


def test_an_undocumented_component_fails():
    bad = GOOD.replace("    !> Its mass [kg].\n", "")
    assert missing_doc_comments(bad) == [f"<text>:{_line(bad, ':: m')} component m"]


def test_a_private_routine_and_a_public_generic():
    """A private routine is not checked; one reached through a public generic is."""
    assert missing_doc_comments(GOOD.replace("public :: thing_type, make, twice",
                                             "public :: thing_type, twice")
                                .replace("    !> The thing made.\n", "")) == []
    generic = GOOD.replace("public :: thing_type, make, twice",
                           "public :: thing_type, twice, build\n"
                           "  interface build\n    module procedure hidden\n  end interface")
    assert missing_doc_comments(generic) == [f"<text>:{_line(generic, ':: u')} hidden(u)"]


def test_a_type_bound_procedure_of_a_public_type_is_checked():
    bound = GOOD.replace("    real :: k = 1.0  !! Its stiffness [N/m].\n",
                         "    real :: k = 1.0  !! Its stiffness [N/m].\n"
                         "  contains\n    procedure :: go => hidden\n")
    assert missing_doc_comments(bound) == [f"<text>:{_line(bound, ':: u')} hidden(u)"]
