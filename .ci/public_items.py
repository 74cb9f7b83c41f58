#!/usr/bin/env python3
"""Counts the public surface reachable from the crate root in rustdoc's JSON output: the items
(structs, enums, functions, constants, statics, traits, type aliases and macros; not modules,
fields or variants), each once however many paths reach it, and the methods and associated
constants and types of their inherent impls (trait impls are the traits' surface, not ours).
Deprecated items are listed apart.

Usage: public_items.py target/doc/bevy_windfall.json [--list] [--max N]
"""
import json
import sys

COUNTED = {"struct", "enum", "function", "constant", "static", "trait", "type_alias", "macro"}


def main():
    path = sys.argv[1]
    listing = "--list" in sys.argv
    limit = int(sys.argv[sys.argv.index("--max") + 1]) if "--max" in sys.argv else None
    doc = json.load(open(path))
    index = doc["index"]
    paths = doc["paths"]
    seen = {}
    deprecated = {}
    visited = set()

    def kind_of(item):
        return next(iter(item["inner"]))

    def walk(module_id, prefix):
        if module_id in visited:
            return
        visited.add(module_id)
        module = index[str(module_id)]
        for child in module["inner"]["module"]["items"]:
            item = index.get(str(child))
            if item is None or item["visibility"] != "public":
                continue
            visit(item, prefix)

    def visit(item, prefix):
        kind = kind_of(item)
        if kind == "module":
            walk(item["id"], prefix + [item["name"]])
        elif kind == "use":
            use = item["inner"]["use"]
            target = use.get("id")
            if target is None:
                return
            target_item = index.get(str(target))
            if target_item is None:
                return  # an external item re-exported
            if use["is_glob"]:
                if kind_of(target_item) == "module":
                    walk(target, prefix)
                return
            renamed = dict(target_item, name=use["name"])
            visit(renamed, prefix)
        elif kind in COUNTED:
            name = "::".join(prefix + [item["name"]])
            bucket = deprecated if item.get("deprecation") else seen
            bucket.setdefault(item["id"], (kind, name))

    walk(doc["root"], ["bevy_windfall"])
    members = {}  # (owner, member) -> kind, for the inherent impls of the items counted
    for item_id, (kind, name) in list(seen.items()) + list(deprecated.items()):
        inner = index[str(item_id)]["inner"].get(kind, {})
        for impl_id in inner.get("impls", []):
            impl = index.get(str(impl_id), {}).get("inner", {}).get("impl")
            if not impl or impl.get("trait") is not None or impl.get("is_synthetic"):
                continue
            for member_id in impl["items"]:
                member = index.get(str(member_id))
                if member is None or member["visibility"] != "public":
                    continue
                member_kind = kind_of(member)
                if member_kind in ("function", "assoc_const", "assoc_type"):
                    members[(name, member["name"])] = member_kind
    if listing:
        for kind, name in sorted(seen.values(), key=lambda x: x[1]):
            print(f"{kind:10} {name}")
        for kind, name in sorted(deprecated.values(), key=lambda x: x[1]):
            print(f"{kind:10} {name} (deprecated)")
        for (owner, member), kind in sorted(members.items()):
            print(f"{kind:10} {owner}::{member}")
    methods = sum(1 for k in members.values() if k == "function")
    print(f"public items reachable from the crate root: {len(seen)}"
          f" (and {len(deprecated)} deprecated); their methods: {methods}, associated"
          f" constants and types: {len(members) - methods}; in all {len(seen) + len(members)}")
    if limit is not None and len(seen) > limit:
        print(f"more than the budget of {limit}", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
