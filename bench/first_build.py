"""The first build's CPU sum, critical path and wall time on two idle cores, from a fresh
`cargo build --release --timings -p stiffid-cli` whose rustc runs were timed (bench/first_build.sh).

Each package weighs its rustc CPU time (user + system; its build script's compilation included),
which the machine's load hardly changes, where the timings' wall times grow with it. The package
graph is `cargo metadata`'s (normal and build dependencies). A crate starts when its normal
dependencies' metadata is ready (cargo's pipelining: their frontend share, from the timings'
sections) and its build dependencies and proc macros are done. The wall time on two cores is a
list schedule: at most two crates at once, a crate's frontend on one thread, its code generation
on both when a core is free (rustc's codegen units through the jobserver).

usage: first_build.py CHECKOUT TIMINGS.html CPU.log"""
import collections
import json
import subprocess
import sys

CORES = 2


def load(root, html, cpulog):
    meta = json.loads(subprocess.check_output(
        ['cargo', 'metadata', '--format-version', '1', '--offline', '--filter-platform',
         'x86_64-unknown-linux-gnu'], cwd=root))
    packages = {p['id']: p for p in meta['packages']}
    nodes = {n['id']: n for n in meta['resolve']['nodes']}
    cli = next(i for i, p in packages.items() if p['name'] == 'stiffid-cli')
    text = open(html).read()
    start = text.index('const UNIT_DATA = ') + len('const UNIT_DATA = ')
    units = json.loads(text[start:text.index('];', start) + 1])
    cpu = collections.defaultdict(list)
    for line in open(cpulog):
        f = line.split()
        if len(f) == 4 and f[1][0].isdigit():
            cpu[f[0]].append((float(f[3]), float(f[1]) + float(f[2])))
    weight, frontend = collections.defaultdict(float), {}
    for u in units:
        if u['mode'] == 'run-custom-build':
            continue
        target = u['target'] or ''
        script = 'build' in target and 'script' in target
        binary = '"bin"' in target
        crate = ('build_script_build' if script else target.split('"')[0].strip() if binary
                 else u['name'].replace('-', '_'))
        runs = cpu.get(crate)
        if runs:  # the run of that crate whose wall time is nearest the unit's
            run = min(runs, key=lambda r: abs(r[0] - u['duration']))
            runs.remove(run)
            w = run[1]
        else:
            w = u['duration'] / 10
        key = (u['name'] + (' (bin)' if binary else ''), u['version'])
        weight[key] += w
        for name, section in u.get('sections') or []:
            if name == 'frontend' and u['duration'] > 0 and not script:
                frontend[key] = section['end'] / u['duration']
    deps, need, stack = {}, set(), [cli]
    while stack:
        x = stack.pop()
        if x in need:
            continue
        need.add(x)
        deps[x] = []
        for d in nodes[x]['deps']:
            kinds = {k['kind'] for k in d['dep_kinds']}
            if not kinds & {None, 'build'}:
                continue
            q = packages[d['pkg']]
            macro = any('proc-macro' in t['kind'] for t in q['targets'])
            deps[x].append((d['pkg'], macro or kinds == {'build'}))
            stack.append(d['pkg'])
    key = {x: (packages[x]['name'], packages[x]['version']) for x in need}
    # The binary links every crate: it waits for all of them; its package's library, if it has
    # one, is pipelined like any other.
    binary = cli + ' (bin)'
    key[binary] = (key[cli][0] + ' (bin)', key[cli][1])
    if weight[key[cli]] == 0:  # no library: the package's dependencies are the binary's
        deps[binary] = [(d, True) for d, _ in deps.pop(cli)]
        del key[cli]
    else:
        deps[binary] = [(cli, True)] + [(d, True) for d, _ in deps[cli]]
    work = {x: weight[key[x]] for x in key}
    front = {x: frontend.get(key[x], 1.0) for x in key}
    return binary, key, deps, work, front


def critical_path(cli, key, deps, work, front):
    start, finish, via = {}, {}, {}

    def visit(x):
        if x in finish:
            return
        s, by = 0.0, None
        for d, full in deps[x]:
            visit(d)
            t = finish[d] if full else start[d] + front[d] * work[d]
            if t > s:
                s, by = t, d
        start[x], finish[x], via[x] = s, s + work[x], by

    visit(cli)
    path, x = [], cli
    while x:
        path.append(x)
        x = via[x]
    return finish[cli], [(start[x], work[x], key[x]) for x in reversed(path)]


def two_cores(cli, deps, work, front):
    left = {x: [front[x] * work[x], (1 - front[x]) * work[x]] for x in work}
    meta, done, running, t = set(), set(), set(), 0.0
    while len(done) < len(work):
        for x in work:
            if x not in running and x not in done and all(
                    (d in done) if full else (d in meta) for d, full in deps[x]):
                running.add(x)
        active = sorted(running, key=lambda x: -sum(left[x]))[:CORES]
        share = {x: 1.0 for x in active}
        spare = CORES - len(active)
        for x in active:
            if spare and left[x][0] <= 1e-9:
                share[x] += spare
                spare = 0
        dt = max(1e-6, min(left[x][0] if left[x][0] > 1e-9 else left[x][1] / share[x]
                           for x in active))
        t += dt
        for x in active:
            if left[x][0] > 1e-9:
                left[x][0] -= dt
                if left[x][0] <= 1e-9:
                    meta.add(x)
            else:
                left[x][1] -= dt * share[x]
            if left[x][0] <= 1e-9 and left[x][1] <= 1e-9:
                meta.add(x)
                done.add(x)
                running.discard(x)
    return t


def main():
    cli, key, deps, work, front = load(*sys.argv[1:4])
    total = sum(work.values())
    length, path = critical_path(cli, key, deps, work, front)
    wall = two_cores(cli, deps, work, front)
    print(f'{len(work)} crates, rustc CPU {total:.1f} s (half: {total / 2:.1f} s)')
    print(f'critical path, CPU-weighted, one thread per crate: {length:.1f} s')
    for s, w, (name, version) in path:
        print(f'  {s:6.1f} s  {w:6.1f} s  {name} {version}')
    top = sorted(((w, key[x][0]) for x, w in work.items()), reverse=True)[:12]
    print('largest: ' + ', '.join(f'{n} {w:.1f} s ({100 * w / total:.1f}%)' for w, n in top))
    print(f'on {CORES} idle cores: {wall:.0f} s ({round(wall) // 60} min {round(wall) % 60} s)')


if __name__ == '__main__':
    main()
