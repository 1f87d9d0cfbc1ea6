document.querySelectorAll('table.sortable th').forEach(function(th,i){
th.title='click to sort';th.onclick=function(){var tb=th.closest('table').tBodies[0];
var rows=Array.from(tb.rows),up=th.dataset.up!=='1';th.dataset.up=up?'1':'0';
rows.sort(function(a,b){var x=a.cells[i].textContent,y=b.cells[i].textContent,
p=parseFloat(x.replace(/[^0-9.eE+-]/g,'')),q=parseFloat(y.replace(/[^0-9.eE+-]/g,''));
var r=(!isNaN(p)&&!isNaN(q))?p-q:x.localeCompare(y);return up?r:-r;});
rows.forEach(function(r){tb.appendChild(r);});};});
document.querySelectorAll('input.filter').forEach(function(f){f.oninput=function(){
var t=document.getElementById(f.dataset.table),q=f.value.toLowerCase();
Array.from(t.tBodies[0].rows).forEach(function(r){
r.style.display=r.textContent.toLowerCase().indexOf(q)<0?'none':'';});};});
document.querySelectorAll('button.more').forEach(function(b){b.onclick=function(){
var t=document.getElementById(b.dataset.table);t.classList.toggle('hide-more');
b.textContent=t.classList.contains('hide-more')?'show all columns':'key columns only';};});
document.querySelectorAll('img.flip').forEach(function(im){im.title='click: flip to the reference';
im.onclick=function(){var r=document.getElementById(im.dataset.ref);if(!r)return;
if(!im.dataset.own){im.dataset.own=im.src;im.src=r.dataset.full||r.src;im.title='reference; click: back';}
else{im.src=im.dataset.own;delete im.dataset.own;im.title='click: flip to the reference';}};});
