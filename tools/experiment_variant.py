"""An experiment's scene, edited, in a scratch folder where its relative paths still resolve: the
folder links to the experiment's own files and to specimens/. Shared by tools/bench_contact.py and
tools/rattle_convergence.py."""
import json
import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def linked_scene(experiment, work, edit):
    """Writes experiments/<experiment>/scene.json, changed by edit(scene) (a dict, edited in place),
    into `work`, beside links to the experiment's other files; returns (path, scene)."""
    src = os.path.join(ROOT, 'experiments', experiment)
    folder = os.path.join(work, 'experiments', experiment)
    os.makedirs(folder, exist_ok=True)
    if not os.path.exists(os.path.join(work, 'specimens')):
        os.symlink(os.path.join(ROOT, 'specimens'), os.path.join(work, 'specimens'))
    for f in os.listdir(src):
        if f != 'scene.json' and not os.path.exists(os.path.join(folder, f)):
            os.symlink(os.path.join(src, f), os.path.join(folder, f))
    with open(os.path.join(src, 'scene.json')) as f:
        scene = json.load(f)
    edit(scene)
    path = os.path.join(folder, 'scene.json')
    with open(path, 'w') as f:
        json.dump(scene, f)
    return path, scene


def finite_links(scene, stiffness_factor):
    """Finite localized links (contact.stiffness_factor) at every interface the scene leaves
    rigid. An interface with a stiffness of its own (a rise_time: imperfect faces at the striker's
    impact) is a finite link already and keeps it, so the loading stays the scene's."""
    contact = scene.setdefault('contact', {})
    contact['stiffness_factor'] = stiffness_factor
