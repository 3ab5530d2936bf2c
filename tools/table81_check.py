# Measures how well Table 8.1 (human arm/leg) alone places elbows, wrists, knees, ankles and toes
# along the MakeHuman reference limb chains (shoulder -> middle fingertip, hip -> toe tip).
# Usage: cd ../shared/refdata && python3 <skelfit>/tools/table81_check.py
import json, glob, math
def sub(a,b): return [x-y for x,y in zip(a,b)]
def add(a,b): return [x+y for x,y in zip(a,b)]
def mul(a,s): return [x*s for x in a]
def norm(a): return math.sqrt(sum(x*x for x in a))
def at(poly, s):
    for a,b in zip(poly, poly[1:]):
        l = norm(sub(b,a))
        if s <= l: return add(a, mul(sub(b,a), s/l if l else 0))
        s -= l
    return poly[-1]
arm=[190,150,20,36,25,15,10]; leg=[180,160,30,30,12,5,5]
rows=[]
for d in sorted(glob.glob('humanoid/mh_*')):
    rig=json.load(open(d+'/rig_game_engine.json'))
    P={j['name']:j['position'] for j in rig['joints']}
    V=[list(map(float,l.split()[1:4])) for l in open(d+'/mesh.obj') if l.startswith('v ')]
    out=[]
    for s in 'lr':
        tip=add(P['middle_03_'+s], sub(P['middle_03_'+s],P['middle_02_'+s]))
        chain=[P['upperarm_'+s],P['lowerarm_'+s],P['hand_'+s],P['middle_01_'+s],P['middle_02_'+s],P['middle_03_'+s],tip]
        L=sum(norm(sub(b,a)) for a,b in zip(chain,chain[1:]))
        c=[sum(arm[:k])/sum(arm) for k in range(len(arm)+1)]
        out.append(('elbow',norm(sub(at(chain,c[1]*L),P['lowerarm_'+s]))))
        out.append(('wrist',norm(sub(at(chain,c[2]*L),P['hand_'+s]))))
        ball=P['ball_'+s]
        cand=[v for v in V if abs(v[0]-ball[0])<0.05 and v[1]<0.04]
        toe=max(cand,key=lambda v:v[2])
        chain=[P['thigh_'+s],P['calf_'+s],P['foot_'+s],ball,toe]
        L=sum(norm(sub(b,a)) for a,b in zip(chain,chain[1:]))
        c=[sum(leg[:k])/sum(leg) for k in range(len(leg)+1)]
        out.append(('knee',norm(sub(at(chain,c[1]*L),P['calf_'+s]))))
        out.append(('ankle',norm(sub(at(chain,c[2]*L),P['foot_'+s]))))
        out.append(('toe',norm(sub(at(chain,c[4]*L),ball))))
    agg={}
    for k,v in out: agg.setdefault(k,[]).append(v*1000)
    print(d.split('/')[-1].ljust(26), '  '.join(f"{k} {sum(v)/len(v):5.1f}" for k,v in agg.items()), 'mm')
