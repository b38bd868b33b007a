"""Plain-text looks into a scene in protobuf text format (a .pbtxt file, or the scene stored in
run.h5), for the scripts that need a field or two without the schema."""
import re


def own_fields(text, name):
    """The body of the first `name { ... }` block of `text` (`name: { ... }` too) with its nested
    blocks blanked out, so that only the block's own fields remain (a tool's pressure_nodes hold
    fields of other messages); None without such a block. Comments must be removed first."""
    m = re.search(r"\b" + re.escape(name) + r"\s*:?\s*\{", text or "")
    if not m:
        return None
    depth, own = 1, []
    for c in text[m.end():]:
        depth += (c == "{") - (c == "}")
        if depth == 0:
            break
        own.append(c if depth == 1 and c != "}" else " ")
    return "".join(own)


def without_comments(text):
    """`text` with its `# ...` comments removed (the scene files hold no '#' inside strings)."""
    return re.sub(r"#[^\n]*", "", text or "")


def scalar_fields(text, name):
    """The numeric fields of the first `name { ... }` block of `text` as {field: float}, its nested
    blocks left out; {} without such a block. Comments are removed here."""
    own = own_fields(without_comments(text), name)
    fields = {}
    for key, value in re.findall(r"(\w+)\s*:\s*([-+]?[0-9.]+(?:[eE][-+]?[0-9]+)?)\b", own or ""):
        fields[key] = float(value)
    return fields
