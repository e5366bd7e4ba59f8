# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
QoS profiles as rosbag2 stores them (``offered_qos_profiles``).

Humble's rosbag2 writes a YAML list, one entry per publisher, with the
policies as rmw's enum numbers and durations as ``{sec, nsec}``
(``9223372036``/``854775807`` for "infinite"); Iron and later write the
policy names. Both are read; the Humble form is written. On the Node side
a profile is the JS object of packages/wasm_js/src/qos.mjs (durations in
milliseconds, 0: none).
"""

from colcon_wasm.error import ColconWasmError
import yaml

HISTORY = {'system_default': 0, 'keep_last': 1, 'keep_all': 2, 'unknown': 3}
RELIABILITY = {'system_default': 0, 'reliable': 1, 'best_effort': 2, 'unknown': 3,
               'best_available': 4}
DURABILITY = {'system_default': 0, 'transient_local': 1, 'volatile': 2, 'unknown': 3,
              'best_available': 4}
LIVELINESS = {'system_default': 0, 'automatic': 1, 'manual_by_node': 2, 'manual_by_topic': 3,
              'unknown': 4, 'best_available': 5}

"""rosbag2's "infinite" duration (Humble: RMW_DURATION_INFINITE split)."""
INFINITE = {'sec': 9223372036, 'nsec': 854775807}

"""The depth a player's publisher gets when the bag does not tell one."""
DEFAULT_DEPTH = 10


def _duration(ms):
    if not ms or ms == float('inf') or ms < 0:
        return dict(INFINITE)
    ns = round(ms * 1e6)
    return {'sec': ns // 1000000000, 'nsec': ns % 1000000000}


def _ms(value):
    if not isinstance(value, dict):
        return 0
    try:
        sec, nsec = int(value.get('sec', 0)), int(value.get('nsec', 0))
    except (TypeError, ValueError, OverflowError):
        # a recorded duration that is not two integers: read as none (a bag's
        # metadata is the recorder's text, not trusted)
        return 0
    if (sec, nsec) == (INFINITE['sec'], INFINITE['nsec']) or sec >= 2147483647 or \
            (sec, nsec) == (0, 0):
        return 0
    return (sec * 1000000000 + nsec) / 1e6


def _depth(value):
    try:
        depth = int(value or 0)
    except (TypeError, ValueError, OverflowError):
        return 0
    return depth if 0 <= depth < 2 ** 31 else 0


def to_rosbag2(profiles):
    """
    Write JS profiles as the ``offered_qos_profiles`` YAML of Humble's rosbag2.

    :param profiles: the QoS of a topic's publishers, JS form
    """
    entries = []
    for q in profiles:
        entries.append({
            'history': HISTORY.get(q.get('history', 'keep_last'), 1),
            'depth': int(q.get('depth', DEFAULT_DEPTH)),
            'reliability': RELIABILITY.get(q.get('reliability', 'reliable'), 1),
            'durability': DURABILITY.get(q.get('durability', 'volatile'), 2),
            'deadline': _duration(q.get('deadlineMs')),
            'lifespan': _duration(q.get('lifespanMs')),
            'liveliness': LIVELINESS.get(q.get('liveliness', 'automatic'), 1),
            'liveliness_lease_duration': _duration(q.get('leaseMs')),
            'avoid_ros_namespace_conventions': False,
        })
    if not entries:
        return ''
    return yaml.safe_dump(entries, default_flow_style=False, sort_keys=False).strip()


def _policy(value, table):
    if isinstance(value, int):
        for name, number in table.items():
            if number == value:
                return name
        return 'unknown'
    return str(value).lower() if isinstance(value, str) else 'unknown'


def from_rosbag2(text):
    """
    Read ``offered_qos_profiles`` (either form) into a list of dicts of policy names.

    :returns: ``[{'history', 'depth', 'reliability', 'durability', 'lifespanMs',
      'deadlineMs', 'liveliness', 'leaseMs'}, ...]``; ``[]`` for none or
      unreadable text
    """
    if not text:
        return []
    try:
        items = yaml.safe_load(text)
    except yaml.YAMLError:
        return []
    if not isinstance(items, list):
        return []
    profiles = []
    for item in items:
        if not isinstance(item, dict):
            continue
        profiles.append({
            'history': _policy(item.get('history'), HISTORY),
            'depth': _depth(item.get('depth')),
            'reliability': _policy(item.get('reliability'), RELIABILITY),
            'durability': _policy(item.get('durability'), DURABILITY),
            'deadlineMs': _ms(item.get('deadline')),
            'lifespanMs': _ms(item.get('lifespan')),
            'liveliness': _policy(item.get('liveliness'), LIVELINESS),
            'leaseMs': _ms(item.get('liveliness_lease_duration')),
        })
    return profiles


def player_qos(text):
    """
    Choose the QoS of a player's publisher for a topic, from its recorded offers.

    As rosbag2's player adapts to the recorded offers: reliability and
    durability are kept when every offer agrees on them (reliable and
    volatile otherwise); history is keep_last with the recorded depth
    (``DEFAULT_DEPTH`` when the bag tells none); lifespan is kept when the
    offers agree.
    """
    offers = from_rosbag2(text)

    def agreed(field, allowed, fallback):
        values = {o[field] for o in offers}
        if len(values) == 1 and next(iter(values)) in allowed:
            return values.pop()
        return fallback

    depths = [o['depth'] for o in offers if o['depth'] > 0 and o['history'] == 'keep_last']
    qos = {
        'history': 'keep_last',
        'depth': max(depths) if depths else DEFAULT_DEPTH,
        'reliability': agreed('reliability', ('reliable', 'best_effort'), 'reliable'),
        'durability': agreed('durability', ('volatile', 'transient_local'), 'volatile'),
    }
    lifespans = {o['lifespanMs'] for o in offers}
    if len(lifespans) == 1 and lifespans != {0}:
        qos['lifespanMs'] = lifespans.pop()
    return qos


class QosOverrideError(ColconWasmError):
    """A QoS override file that cannot be used: the text names the file, topic and key."""


_OVERRIDE_POLICIES = {
    'history': ('keep_last', 'keep_all', 'system_default'),
    'reliability': ('reliable', 'best_effort', 'system_default'),
    'durability': ('volatile', 'transient_local', 'system_default'),
    'liveliness': ('automatic', 'manual_by_topic', 'system_default'),
}
_OVERRIDE_DURATIONS = {'deadline': 'deadlineMs', 'lifespan': 'lifespanMs',
                       'liveliness_lease_duration': 'leaseMs'}
_OVERRIDE_TABLES = {'history': HISTORY, 'reliability': RELIABILITY, 'durability': DURABILITY,
                    'liveliness': LIVELINESS}


def read_overrides(path):
    """
    Read a QoS override file, as ``ros2 bag play --qos-profile-overrides-path`` does.

    The file maps topic names to profiles: ``history`` (``keep_last``,
    ``keep_all``), ``depth``, ``reliability`` (``reliable``,
    ``best_effort``), ``durability`` (``volatile``, ``transient_local``),
    ``deadline``, ``lifespan``, ``liveliness_lease_duration`` (``{sec,
    nsec}``), ``liveliness`` (``automatic``, ``manual_by_topic``) and
    ``avoid_ros_namespace_conventions``; policies as names or as rmw's enum
    numbers. What a profile leaves out is rclcpp's default (keep_last 10,
    reliable, volatile).

    :returns: ``{topic: profile}``, profiles in the JS form (qos.mjs)
    :raises QosOverrideError: naming the file, the topic and the key
    """
    try:
        with open(path, encoding='utf-8') as f:
            data = yaml.safe_load(f)
    except OSError as e:
        raise QosOverrideError(f"cannot read the QoS override file '{path}': "
                               f'{e.strerror or e}') from None
    except UnicodeDecodeError as e:
        raise QosOverrideError(f"the QoS override file '{path}' is not UTF-8 text: "
                               f'{e.reason} at byte {e.start}') from None
    except yaml.YAMLError as e:
        raise QosOverrideError(f"the QoS override file '{path}' is not YAML: {e}") from None
    if not isinstance(data, dict):
        raise QosOverrideError(f"the QoS override file '{path}' must map topic names to "
                               'profiles (e.g. "/chatter: {reliability: best_effort}")')
    overrides = {}
    for topic, item in data.items():
        where = f"QoS override file '{path}', topic {topic!r}"
        if not isinstance(topic, str) or not isinstance(item, dict):
            raise QosOverrideError(f'{where}: expected a topic name and a mapping of policies')
        profile = {'history': 'keep_last', 'depth': DEFAULT_DEPTH, 'reliability': 'reliable',
                   'durability': 'volatile'}
        for key, value in item.items():
            if key in _OVERRIDE_POLICIES:
                name = _policy(value, _OVERRIDE_TABLES[key])
                if name not in _OVERRIDE_POLICIES[key]:
                    raise QosOverrideError(
                        f'{where}: {key} {value!r} is none of '
                        f"{', '.join(_OVERRIDE_POLICIES[key])}")
                if name != 'system_default':
                    profile[key] = name
            elif key == 'depth':
                if not isinstance(value, int) or isinstance(value, bool) or value < 0:
                    raise QosOverrideError(f'{where}: depth {value!r} is not a whole number')
                profile['depth'] = value or DEFAULT_DEPTH
            elif key in _OVERRIDE_DURATIONS:
                if not isinstance(value, dict) or set(value) - {'sec', 'nsec'} or not all(
                        isinstance(v, int) and v >= 0 for v in value.values()):
                    raise QosOverrideError(f'{where}: {key} must be {{sec: S, nsec: N}}, '
                                           f'got {value!r}')
                ms = _ms(value)
                if ms:
                    profile[_OVERRIDE_DURATIONS[key]] = ms
            elif key != 'avoid_ros_namespace_conventions':
                raise QosOverrideError(
                    f"{where}: unknown key '{key}' (keys: history, depth, reliability, "
                    'durability, deadline, lifespan, liveliness, liveliness_lease_duration, '
                    'avoid_ros_namespace_conventions)')
        overrides[topic if topic.startswith('/') else f'/{topic}'] = profile
    return overrides
