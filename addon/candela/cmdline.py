"""Command-line overrides after `--`, like Cycles' `--cycles-device`:

    blender -b scene.blend -E CANDELA -f 1 -- --candela-samples 512 --candela-seed 7

`--candela-memory-limit-mb N` refuses renders predicted to need more than N MB (instead of the machine's available
memory): a farm task then fails with a clear message rather than swapping or being killed.

Unknown arguments are ignored: the part after `--` belongs to every script in the process.
"""

import sys

# flag → (params key, converter)
OPTIONS = {
    "--candela-samples": ("samples", int),
    "--candela-seed": ("seed", int),
    "--candela-memory-limit-mb": ("memory_limit_mb", float),
}


def overrides(argv=None):
    """{params key: value} from the arguments after the first `--` ("--flag N" or "--flag=N")."""
    argv = sys.argv if argv is None else argv
    if "--" not in argv:
        return {}
    args = argv[argv.index("--") + 1:]
    result = {}
    i = 0
    while i < len(args):
        flag, value = args[i], None
        if "=" in flag:
            flag, value = flag.split("=", 1)
        elif flag in OPTIONS and i + 1 < len(args):
            value = args[i + 1]
            i += 1
        if flag in OPTIONS and value is not None:
            key, convert = OPTIONS[flag]
            try:
                result[key] = convert(value)
            except ValueError:
                print(f"Candela: ignoring {flag} {value!r}: not a number")
        i += 1
    return result
